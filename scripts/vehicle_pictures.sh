#!/usr/bin/env bash
# Pictures of the vehicle-on-bridge models (docs/images/), made with
# `mbfe simulate` and gnuplot, against the vehicle's position along the bridge:
#   docs/images/bridge_moving_force.png      midspan deflection, dynamic against the static influence line
#   docs/images/bridge_moving_mass.png       deflection under the wheel and tyre force, wheel against force
#   docs/images/bridge_two_axle_vehicle.png  deflection under each axle and the tyre forces
#   docs/images/mbfe_plot_crossing.png       the same crossing by `mbfe plot --x` (two panels, units)
# Usage: scripts/vehicle_pictures.sh [path/to/mbfe]   (default build/bin/mbfe)
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=${1:-build/bin/mbfe}
[[ -x $mbfe ]] || { echo "vehicle_pictures: no $mbfe (run scripts/build.sh first)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "vehicle_pictures: needs gnuplot (scripts/install-deps.sh)" >&2; exit 2; }
out=docs/images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$out"

# Each model as shipped (adjusted damping, RK4 at 1e-3 s, its limit).
"$mbfe" simulate models/bridge_moving_force.yaml --probe deck@10 --out "$tmp/force.csv" --quiet
"$mbfe" simulate models/bridge_moving_mass.yaml --probe deck@10 --out "$tmp/mass.csv" --quiet
"$mbfe" simulate models/bridge_two_axle_vehicle.yaml --probe deck@10 --out "$tmp/truck.csv" --quiet

# The static influence line of midspan deflection for a load P at s (m),
# P s (3 L^2 - 4 s^2) / (48 EI) for s <= L/2, symmetric; L = 20, EI = 2.1e7.
gnuplot <<GNUPLOT
set datafile separator ","
set terminal pngcairo size 1000,520 font ",11"
set grid
set key top right

set output "$out/bridge_moving_force.png"
set title "bridge\\\_moving\\\_force: 9810 N crossing a 20 m bridge at 20 m/s (alpha = 0.245)"
set xlabel "position of the force s = 20 t (m)"
set ylabel "midspan deflection (mm)"
set xrange [0:30]
L = 20.0; EI = 2.1e7; P = 9810.0
infl(s) = (s < 0 || s > L) ? 0 : (s <= L/2 ? P*s*(3*L*L - 4*s*s)/(48*EI) : P*(L-s)*(3*L*L - 4*(L-s)**2)/(48*EI))
plot "$tmp/force.csv" using (20*\$1):(-1000*\$2) with lines lw 2 title "mbfe: dynamic (FE, 40 elements)", \
     "$tmp/force.csv" using (20*\$1):(1000*infl(20*\$1)) with lines dt 2 lw 2 title "static influence line"

set output "$out/bridge_moving_mass.png"
set multiplot layout 2,1 title "bridge\\\_moving\\\_mass: a 1000 kg wheel on a unilateral tyre crossing at 20 m/s (static start)"
set xrange [0:24]
set title ""
set xlabel ""
set ylabel "deflection under the wheel (mm)"
plot "$tmp/mass.csv" using 2:(1000*column("deflection_tyre")) with lines lw 2 title "deck under the wheel", \
     "$tmp/mass.csv" using 2:(1000*column("deck@10")) with lines lw 1 title "deck at midspan"
set xlabel "wheel position x (m); the deck ends at 20 m"
set ylabel "tyre force (N)"
plot "$tmp/mass.csv" using 2:(column("force_tyre")) with lines lw 2 title "force\\\_tyre (compression)"
unset multiplot

set output "$out/bridge_two_axle_vehicle.png"
set multiplot layout 2,1 title "bridge\\\_two\\\_axle\\\_vehicle: 9 t sprung vehicle, 4 m wheelbase, 20 m/s; approach | deck 0..20 m | exit"
set xrange [-8:28]
set xlabel ""
set ylabel "deck deflection under the axle (mm)"
plot "$tmp/truck.csv" using (\$2-5+2):(1000*column("deflection_front_deck")) with lines lw 2 title "front axle", \
     "$tmp/truck.csv" using (\$2-5-2):(1000*column("deflection_rear_deck")) with lines lw 2 title "rear axle"
set xlabel "axle position x (m)"
set ylabel "tyre force (kN)"
plot "$tmp/truck.csv" using (\$2-5+2):((column("force_front_approach")+column("force_front_deck")+column("force_front_exit"))/1000) with lines lw 2 title "front tyre", \
     "$tmp/truck.csv" using (\$2-5-2):((column("force_rear_approach")+column("force_rear_deck")+column("force_rear_exit"))/1000) with lines lw 2 title "rear tyre"
unset multiplot
GNUPLOT
"$mbfe" simulate models/bridge_moving_mass.yaml --probe deck@10 --out "$tmp/mass_plot.csv" --quiet
"$mbfe" plot "$tmp/mass_plot.csv" -o "$out/mbfe_plot_crossing.png" --x carriage \
  --columns deflection_tyre,deck@10,force_tyre,carriage_drive \
  --title "mbfe plot crossing.csv --x carriage --columns deflection_tyre,deck@10,force_tyre,carriage_drive"
echo "vehicle_pictures: wrote $out/mbfe_plot_crossing.png"
echo "vehicle_pictures: wrote $out/bridge_moving_force.png $out/bridge_moving_mass.png $out/bridge_two_axle_vehicle.png"

#!/usr/bin/env bash
# The accuracy estimate against measured errors (docs/damping-adjustment.md,
# "The accuracy estimate"): each case is one adjusted `mbfe simulate` run with
# `--check-adjustment` over its whole length (the original model,
# generalized-alpha, at the same step), and prints one markdown row: the
# linearised run's estimate, the point figure, the measured contact-force
# difference, their ratio and the estimate's wall time.
#
#   scripts/adjustment_estimate_table.sh [CASE...]     (default: every case)
#
# Needs build/bin/mbfe. About 20 minutes for every case on 2 cores shared with other builds.
set -euo pipefail
cd "$(dirname "$0")/.."
mbfe=build/bin/mbfe
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

veh=models/vehicle_bridge_30m.yaml
mm=models/bridge_moving_mass.yaml
every_beam() {  # every_beam "a b c" KEY VALUE: --set on each beam's adjustment block
  local b
  for b in $1; do printf -- '--set beams.%s.adjustment.%s=%s ' "$b" "$2" "$3"; done
}
vb="approach deck exit"
declare -A cases=(
  [veh30_mass2000]="$veh 2e-5 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit 2000)"
  [veh30_mass1000]="$veh 2e-5 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit 1000)"
  [veh30_mass4000]="$veh 2e-5 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit 4000)"
  [veh30_auto]="$veh 2e-5 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit auto)"
  [veh30_cap2000]="$veh 2e-5 $(every_beam "$vb" policy cap) $(every_beam "$vb" omega_limit 2000)"
  [veh30_cap10000]="$veh 2e-5 $(every_beam "$vb" policy cap) $(every_beam "$vb" omega_limit 10000)"
  [veh60_mass2000]="$veh 2e-5 --set beams.deck.elements=60 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit 2000)"
  [veh60_mass1000]="$veh 2e-5 --set beams.deck.elements=60 $(every_beam "$vb" policy mass) $(every_beam "$vb" omega_limit 1000)"
  [veh60_cap2000]="$veh 2e-5 --set beams.deck.elements=60 $(every_beam "$vb" policy cap) $(every_beam "$vb" omega_limit 2000)"
  [mm_mass2000]="$mm 2e-5 $(every_beam deck policy mass) $(every_beam deck omega_limit 2000)"
  [mm_mass1000]="$mm 2e-5 $(every_beam deck policy mass) $(every_beam deck omega_limit 1000)"
  [mm_cap2000]="$mm 2e-5 $(every_beam deck policy cap) $(every_beam deck omega_limit 2000)"
  [platform_mass]="models/paper_platform.yaml 1e-5 $(every_beam "beam1 beam2" policy mass) $(every_beam "beam1 beam2" zeta_min 0)"
  [platform_cap]="models/paper_platform.yaml 1e-5 $(every_beam "beam1 beam2" policy cap) $(every_beam "beam1 beam2" zeta_min 0)"
  [catenary_mass1500]="models/pantograph_catenary_2span.yaml 1e-4 $(every_beam "messenger contact_wire" policy mass)"
  [catenary_mass1279]="models/pantograph_catenary_2span.yaml 1e-4 $(every_beam "messenger contact_wire" policy mass) $(every_beam "messenger contact_wire" omega_limit 1279)"
  [catenary_cap1500]="models/pantograph_catenary_2span.yaml 1e-4 $(every_beam "messenger contact_wire" policy cap)"
)
order=(veh30_mass1000 veh30_mass2000 veh30_mass4000 veh30_auto veh30_cap2000 veh30_cap10000 veh60_mass1000 veh60_mass2000
       veh60_cap2000 mm_mass1000 mm_mass2000 mm_cap2000 platform_mass platform_cap catenary_mass1500 catenary_cap1500 catenary_mass1279)
[ $# -gt 0 ] && order=("$@")

echo "| case | estimate (linearised run) | point figure | measured contact force | measured / estimate | estimate's time |"
echo "|---|---|---|---|---|---|"
for name in "${order[@]}"; do
  read -r model step rest <<<"${cases[$name]}"
  t_end=$(sed -n 's/.*t_end: *\([0-9.e-]*\).*/\1/p' "$model" | head -1)
  # shellcheck disable=SC2086
  "$mbfe" simulate "$model" $rest --integrator rk4 --step "$step" --every 10 --check-adjustment "$t_end" \
    --out "$out/$name.csv" 2>"$out/$name.log" || { echo "| $name | run failed: $(tail -1 "$out/$name.log") |"; continue; }
  python3 - "$name" "$out/$name.csv.json" <<'PY'
import json, sys
name, path = sys.argv[1], sys.argv[2]
rec = json.load(open(path))
e, c = rec["adjustment_estimate"], rec["adjustment_check"]
points = max([p["estimate"] for p in e["points"]] or [0.0])
lin = e.get("linearised", {})
measured = c["contact_force"]["relative"]
if "contact_force" in lin:
    est = lin["contact_force"]["relative"]
    where = lin["contact_force"]["contact"]
    ratio = f"{measured / est:.2f}" if est > 0 else "-"
    cost = f"{lin['seconds']:.2f} s ({lin['steps']} steps)"
    est_text = f"{100 * est:.3g} % ({where})"
else:
    ratio, cost = "-", "-"
    est_text = "not made: " + lin.get("not_estimated", "")
print(f"| {name} | {est_text} | {100 * points:.3g} % | {100 * measured:.3g} % ({c['contact_force']['column']}) | {ratio} | {cost} |")
PY
done

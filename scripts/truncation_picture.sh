#!/usr/bin/env bash
# Draws docs/images/catenary_truncation.png: CPU time of a whole run against
# the largest error of the EN 50318 contact-force statistics, for the ways of
# running the catenary (docs/catenary.md, "Modal truncation"), at 300 km/h
# (top: a loaded host, 2026-11-24) and 250 km/h (bottom: second runs on a
# quiet host, 2026-11-28; the rows do not compare). The
# figures are those measured for that section (docs/performance.md,
# "Modal truncation of the catenary" gives the commands); they are written
# here, not recomputed.
#
#   scripts/truncation_picture.sh
set -euo pipefail
cd "$(dirname "$0")/.."
command -v gnuplot >/dev/null || { echo "truncation_picture: gnuplot is missing (Debian: gnuplot-nox)" >&2; exit 2; }
data=$(mktemp)
trap 'rm -f "$data"' EXIT
# method (0 adjusted, 1 truncated, 2 original, 3 policy mass at 4000 rad/s, RK4 5e-4 s), worst error (% of the mean force),
# CPU (s, user + system; the mean of the runs (three on the ten-span, two on the two-span), but on the ten-span 100 Hz: its one run, slicing its
# modes, and 200 Hz: its second run, the first having sliced them; at 250 km/h the mean of two second runs), label
cat > "$data" <<'DATA'
# two-span: adjusted (cap 1500 rad/s, RK4 1e-3 s)
0 0.293 2.72 "cap"
# two-span: truncated, RK4 1e-3 s, omega_T 628 942 1257 1500 rad/s
1 1.970 2.45 "100 Hz"
1 0.886 2.59 "150 Hz"
1 0.317 2.69 ""
1 0.261 2.72 "239, 200 Hz"
# two-span: original, generalized-alpha 2e-4 and 1e-4 s
2 0.043 5.13 "2e-4 s"
2 0.008 6.45 "1e-4 s"


# ten-span
0 0.301 37.9 "cap"
1 3.147 17.6 "100 Hz (modes sliced)"
1 0.212 19.2 "200 Hz"
1 0.216 20.6 "239 Hz"


# two-span, 250 km/h: adjusted (cap 1500 rad/s, RK4 1e-3 s)
0 0.296 0.71 "cap"
# truncated, RK4 1e-3 s, omega_T 942 1257 1500 rad/s
1 0.481 0.22 "150 Hz"
1 0.264 0.24 ""
1 0.181 0.26 "239, 200 Hz"
# original, generalized-alpha 2e-4 and 1e-4 s; policy mass at 4000 rad/s, RK4 5e-4 s
2 0.024 2.62 "2e-4 s"
2 0.005 4.05 "1e-4 s"
3 0.036 2.54 "mass 4000"


# ten-span, 250 km/h
0 0.261 19.8 "cap"
1 4.191 5.9 "100 Hz"
1 0.770 7.1 "150 Hz"
1 0.177 9.0 ""
1 0.211 10.0 "239, 200 Hz"
2 0.022 64.3 "2e-4 s"
2 0.006 104.5 "1e-4 s"
3 0.018 51.1 "mass 4000"
DATA
gnuplot <<GP
set terminal pngcairo size 1100,900 font "sans,10"
set output "docs/images/catenary_truncation.png"
set multiplot layout 2,2
set logscale x
set xlabel "largest error of the contact-force statistics (% of the mean force)"
set ylabel "CPU time of the whole run (s)"
set grid
set key top right
set yrange [0:*]
set title "two-span catenary, 300 km/h (1.39 s simulated; loaded host)"
plot "$data" index 0 using 2:(\$1==0?\$3:1/0) with points pt 7 ps 1.5 lc rgb "#1f77b4" title "adjusted (cap), RK4", \
     "" index 0 using 2:(\$1==1?\$3:1/0) with linespoints pt 5 ps 1.2 lc rgb "#d62728" title "truncated, RK4", \
     "" index 0 using 2:(\$1==1?\$3:1/0):4 with labels offset 0,1 font ",9" notitle, \
     "" index 0 using 2:(\$1==2?\$3:1/0) with linespoints pt 9 ps 1.5 lc rgb "#2ca02c" title "original, generalized-alpha", \
     "" index 0 using 2:(\$1==2?\$3:1/0):4 with labels offset 0,1 font ",9" notitle
set title "ten-span catenary, 300 km/h (7.15 s simulated; loaded host)"
set yrange [0:*]
plot "$data" index 1 using 2:(\$1==0?\$3:1/0) with points pt 7 ps 1.5 lc rgb "#1f77b4" title "adjusted (cap), RK4", \
     "" index 1 using 2:(\$1==1?\$3:1/0) with points pt 5 ps 1.2 lc rgb "#d62728" title "truncated, RK4", \
     "" index 1 using 2:(\$1==1?\$3:1/0):4 with labels offset 0,1 font ",9" notitle
do for [panel=2:3] {
  set title (panel == 2 ? "two-span catenary, 250 km/h (1.67 s simulated; quiet host, second runs)" : "ten-span catenary, 250 km/h (8.58 s simulated; quiet host, second runs)")
  set yrange [0:*]
  plot "$data" index panel using 2:(\$1==0?\$3:1/0) with points pt 7 ps 1.5 lc rgb "#1f77b4" title "adjusted (cap), RK4", \
       "" index panel using 2:(\$1==1?\$3:1/0) with linespoints pt 5 ps 1.2 lc rgb "#d62728" title "truncated, RK4", \
       "" index panel using 2:(\$1==1?\$3:1/0):4 with labels offset 0,1 font ",9" notitle, \
       "" index panel using 2:(\$1==2?\$3:1/0) with linespoints pt 9 ps 1.5 lc rgb "#2ca02c" title "original, generalized-alpha", \
       "" index panel using 2:(\$1==2?\$3:1/0):4 with labels offset 0,1 font ",9" notitle, \
       "" index panel using 2:(\$1==3?\$3:1/0) with points pt 13 ps 1.5 lc rgb "#9467bd" title "adjusted (mass 4000 rad/s), RK4 5e-4 s"
}
unset multiplot
GP
echo "truncation_picture: wrote docs/images/catenary_truncation.png"

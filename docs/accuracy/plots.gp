# Draws the accuracy-vs-time plots from accuracy_bench's data files.
# Run by scripts/accuracy.sh from the directory holding the data.
set terminal pngcairo size 1100,700 noenhanced
set datafile separator whitespace
set format y '%.0e'
set grid

set output 'accuracy-vs-time.png'
set title 'Contact depth error against query time (median), per knob'
set logscale xy
set xlabel 'median time per contact query (us)'
set ylabel 'worst depth error over 16 poses, against the reference shape (m)'
set key bottom left box opaque
families = system('cat families')
n = words(families)
# Lines join the points of a resolution sweep only: the other knobs'
# points are alternatives, not a series.
is_sweep(i) = strstrt(word(families, i + 1), 'resolution') > 0
plot for [i=0:n-1] 'accuracy.dat' index i using 3:4:2 with labels left offset 0.5,0 font ',7' notitle, \
     for [i=0:n-1] 'accuracy.dat' index i using 3:(is_sweep(i) ? $4 : 1/0) with lines linecolor i + 1 notitle, \
     for [i=0:n-1] 'accuracy.dat' index i using 3:4 with points pointtype 7 linecolor i + 1 title word(families, i+1)

set output 'step-length.png'
set title 'Approaching a surface in steps of 0.5 to 30 mm: depth reached before contact is reported'
set xlabel 'median time of the step check that reports the contact (us)'
set ylabel 'worst over 64 approaches (m)'
set yrange [1e-5:0.1]
set key top left box opaque
plot 'step.dat' using 2:3:1 with labels left offset 0.5,0 font ',7' notitle, \
     'step.dat' using 2:3 with points pointtype 7 title 'overshoot: depth when the contact is reported', \
     'step.dat' using 2:4 with points pointtype 6 title 'first-touch error (the 1,280-face sphere against the smooth one)'

set output 'tunnelling.png'
set title 'Passes through a 1 mm plate missed, against time per step'
unset logscale y
set logscale x
set format y '%g'
set xlabel 'median time per step check (us)'
set ylabel 'passes missed (%)'
set yrange [-5:105]
unset key
plot 'tunnelling.dat' using 2:3:1 with labels left offset 0.5,0 font ',7' notitle, \
     'tunnelling.dat' using 2:3 with points pointtype 7 notitle

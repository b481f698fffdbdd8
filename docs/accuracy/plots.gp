# Draws the accuracy-vs-time plots from accuracy_bench's data files.
# Run by scripts/accuracy.sh from the directory holding the data.
set terminal pngcairo size 900,600 noenhanced
set datafile separator whitespace

set output 'accuracy-vs-time.png'
set title 'Contact depth error against query time (median), per knob'
set logscale xy
set xlabel 'median time per contact query (us)'
set ylabel 'worst depth error over 16 poses against the reference shape (m)'
set key outside right
set grid
families = system('cat families')
n = words(families)
plot for [i=0:n-1] 'accuracy.dat' index i using 3:4:2 with labels left offset 0.5,0 font ',7' notitle, \
     for [i=0:n-1] 'accuracy.dat' index i using 3:4 with points pointtype 7 title word(families, i+1)

set output 'step-length.png'
set title 'Approaching a surface: how deep the tool sinks before contact is reported, against the time of that step'
set xlabel 'median time of the step check that reports the contact (us)'
set ylabel 'worst depth reached before the report / error of the first touch (m)'
plot 'step.dat' using 2:3:1 with labels left offset 0.5,0 font ',7' notitle, \
     'step.dat' using 2:3 with points pointtype 7 title 'overshoot (depth when reported)', \
     'step.dat' using 2:4 with points pointtype 6 title 'first-touch error (facets of the 1,280-face sphere)'

set output 'tunnelling.png'
set title 'Passes through a 1 mm plate missed, against time per step'
unset logscale y
set logscale x
set xlabel 'median time per step check (us)'
set ylabel 'passes missed (%)'
set yrange [-5:105]
plot 'tunnelling.dat' using 2:3:1 with labels left offset 0.5,0 font ',7' notitle, \
     'tunnelling.dat' using 2:3 with points pointtype 7 notitle

#!/usr/bin/perl -p
# Doxygen's input filter (docs/Doxyfile.in, INPUT_FILTER): in comments, "#V" is the house style
# for "the number of V" (libigl's "V  #V by 3"), which Doxygen would read as a link to a member
# named V; escape it. Lines are kept one for one, so warnings name the right line.
s{(//.*)}{ my $c = $1; $c =~ s/(?<![\\\w&])#(?=[A-Za-z])/\\#/g; $c }e;

#!/usr/bin/perl
# Writes src/io/svg_vertical.c: the ranges of code points whose Unicode
# Vertical_Orientation (UAX #50) is U, Tu or Tr, from Perl's own Unicode
# database, so that the table follows a Unicode version without a data
# file in the tree.  Every other code point is R (turned sideways).
#     perl scripts/gen-vertical-orientation.pl > src/io/svg_vertical.c
use strict;
use warnings;
use Unicode::UCD ();

my @ranges;
my ($cur, $start) = ('R', 0);
for my $c (0 .. 0x110000) {
    my $v = 'R';
    if ($c <= 0x10FFFF) {
        my $ch = chr($c);
        $v = $ch =~ /\p{vo=U}/ ? 'U' : $ch =~ /\p{vo=Tu}/ ? 'TU' : $ch =~ /\p{vo=Tr}/ ? 'TR' : 'R';
    }
    if ($v ne $cur) {
        push @ranges, [$start, $c - 1, $cur] if $cur ne 'R';
        ($cur, $start) = ($v, $c);
    }
}
my $unicode = Unicode::UCD::UnicodeVersion();
print <<"HEAD";
/* svg_vertical.c - the Unicode Vertical_Orientation of the code points
 * that are not R (UAX #50, Unicode $unicode), which decides whether a
 * character stands upright in vertical SVG text (svg_text.c looks them
 * up).  Written by scripts/gen-vertical-orientation.pl from Perl's
 * Unicode database: do not edit. */
#include "svg_text.h"

const svg_vo_range svg_vo_ranges[] = {
HEAD
for my $r (@ranges) {
    printf "    { 0x%04X, 0x%04X, SVG_VO_%s },\n", @$r;
}
print "};\n\nconst int svg_vo_range_count = (int)(sizeof svg_vo_ranges / sizeof svg_vo_ranges[0]);\n";

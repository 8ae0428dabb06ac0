/*
 * population_csv.h - a population read from a CSV file in ANSUR II's layout.
 *
 * A header, then one row a person. Columns named as ANSUR II's measured
 * dimensions (any case) are measures; a sex column, `Gender` or `sex`,
 * holds Male/Female (or M/F, any case); every other column (ids, dates,
 * demographics) is ignored. Units are ANSUR II's: millimetres, weightkg in
 * tenths of a kilogram (the population holds kilograms). UTF-8, with or
 * without a byte order mark, or latin-1: only ASCII matters (the names and
 * numbers); LF or CRLF line ends; fields may be quoted as RFC 4180 says
 * ("a ""b"", c"), each on its own line.
 */
#ifndef POSTURE_POPULATION_CSV_H
#define POSTURE_POPULATION_CSV_H

#include <stddef.h>

#include "figure/population.h"

/*
 * Reads a population from text (len bytes; file names it in messages).
 * Refused, with "FILE:LINE: why" in err and NULL returned (nothing made):
 * no header, or one without a sex column or a measure column, a column
 * twice; a row with another number of fields than the header; an empty or
 * unknown sex; a measure's cell that is empty, not a plain decimal number,
 * or outside population_bounds (half ANSUR II's smallest to twice its
 * largest); a NUL byte; a quote that does not close on its line; a sex
 * with 1 to 29 people, or no people at all. ignored, when not NULL, gets
 * the ignored columns' names, comma-separated, non-ASCII bytes as '?', cut
 * at ignored_len.
 */
struct population *population_csv_read(const char *text, size_t len, const char *file,
				       char *ignored, size_t ignored_len, char *err, size_t errlen);

#endif

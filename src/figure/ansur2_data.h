/*
 * ansur2_data.h - the built-in population ansur2: the statistics of the
 * ANSUR II public working data that tools/ansur2-stats derives from
 * the two CSV files of data/ansur2/ into ansur2_data.c (see its README).
 *
 * Columns are the files' 93 measured dimensions in the files' order; units
 * millimetres, weightkg in kilograms. Covariances are the lower triangle,
 * row by row: element (i, j), j <= i, at i * (i + 1) / 2 + j.
 */
#ifndef POSTURE_ANSUR2_DATA_H
#define POSTURE_ANSUR2_DATA_H

#define ANSUR2_NCOL 93
#define ANSUR2_NTRI (ANSUR2_NCOL * (ANSUR2_NCOL + 1) / 2)
#define ANSUR2_N_MALE 4082
#define ANSUR2_N_FEMALE 1986

extern const char *const ansur2_names[ANSUR2_NCOL];
extern const double ansur2_min[ANSUR2_NCOL], ansur2_max[ANSUR2_NCOL];
extern const double ansur2_mean_male[ANSUR2_NCOL], ansur2_mean_female[ANSUR2_NCOL];
extern const double ansur2_cov_male[ANSUR2_NTRI], ansur2_cov_female[ANSUR2_NTRI];
/* every stature of the sex, ascending (mm) */
extern const double ansur2_stature_male[ANSUR2_N_MALE], ansur2_stature_female[ANSUR2_N_FEMALE];

#endif

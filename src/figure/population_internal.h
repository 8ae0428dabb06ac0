/* population_internal.h - what the population's readers share */
#ifndef POSTURE_POPULATION_INTERNAL_H
#define POSTURE_POPULATION_INTERNAL_H

#include "figure/population.h"

/*
 * A new population that owns its arrays: every column lacking, no people.
 * Its mean and cov point into arrays the caller may fill (cast away the
 * const); population_free frees them and any stature arrays it is given.
 * NULL when out of memory.
 */
struct population *population_new_owned(void);

#endif

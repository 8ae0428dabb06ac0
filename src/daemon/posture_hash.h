/*
 * posture_hash.h - postures as numbers (FNV-1a over the bytes of the
 * values, so equal numbers mean equal postures bit for bit, but for
 * collisions): what the journal compares to know what changed, what a
 * recording's frame log holds and a replay checks (tape.h), and what
 * `status` reports.
 */
#ifndef POSTURE_DAEMON_POSTURE_HASH_H
#define POSTURE_DAEMON_POSTURE_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "pose/env.h"

#define POSTURE_FNV_BASIS 14695981039346656037ull

/* h continued over n bytes at p */
uint64_t posture_fnv(uint64_t h, const void *p, size_t n);
/* a figure's posture, and its behaviours' state and goals */
uint64_t posture_figure_hash(const struct env_figure *f);
/* every figure of e, with its slot */
uint64_t posture_env_hash(const struct env *e);

#endif

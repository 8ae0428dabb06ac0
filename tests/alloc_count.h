/*
 * alloc_count.h - counts the test program's heap calls, to prove a path
 * allocates nothing (or frees all it takes). Include once, in one test
 * program: it defines malloc, calloc, realloc and free. Not under ASan,
 * which owns malloc: there COUNT_ALLOCS is 0 and nothing is defined.
 */
#ifndef POSTURE_ALLOC_COUNT_H
#define POSTURE_ALLOC_COUNT_H

#include <stddef.h>

#if defined(__SANITIZE_ADDRESS__)
#define COUNT_ALLOCS 0
#else
#define COUNT_ALLOCS 1
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void __libc_free(void *);
static long allocs, frees;
void *malloc(size_t n);
void *calloc(size_t n, size_t k);
void *realloc(void *p, size_t n);
void free(void *p);
void
free(void *p)
{
	if (p)
		frees++;
	__libc_free(p);
}
void *
malloc(size_t n)
{
	allocs++;
	return __libc_malloc(n);
}
void *
calloc(size_t n, size_t k)
{
	allocs++;
	return __libc_calloc(n, k);
}
void *
realloc(void *p, size_t n)
{
	allocs++;
	return __libc_realloc(p, n);
}
#endif

#endif

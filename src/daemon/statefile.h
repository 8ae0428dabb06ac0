/* statefile.h - whole-file reads and atomic writes for the state directory */
#ifndef POSTURE_STATEFILE_H
#define POSTURE_STATEFILE_H

#include <stddef.h>

#define STATEFILE_MAX (16u << 20) /* the largest file read whole */

/*
 * Reads a regular file (no symlink as the last component) into a malloc'd,
 * NUL-terminated buffer. Returns NULL with errno set (EFBIG when too big).
 */
char *statefile_read(const char *path, size_t *len);

/*
 * Writes data to path atomically: a temporary file in the same directory,
 * fsync, rename over path, fsync of the directory. 0, or -1 with errno.
 */
int statefile_write(const char *path, const void *data, size_t len);

/* all len bytes to fd, through short writes and EINTR: 0, or -1 with errno */
int statefile_write_all(int fd, const void *data, size_t len);

#endif

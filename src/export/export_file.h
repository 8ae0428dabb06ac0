/*
 * export_file.h - how every export reaches the disk: the file written
 * under a temporary name beside its place and renamed over it once
 * complete, so a reader (or a failed export) never sees half a file.
 */
#ifndef POSTURE_EXPORT_FILE_H
#define POSTURE_EXPORT_FILE_H

#include <stddef.h>
#include <stdio.h>

struct export_file {
	FILE *f;
	char path[4096];
	char tmp[4096 + 16];
};

/*
 * Opens path for writing, never through a symbolic link (an export names
 * files beside the one the caller checked: a link planted there must not
 * lead elsewhere). NULL with errno on failure.
 */
FILE *export_fopen(const char *path);

/* opens the temporary file for path; the stream, or NULL with why in err */
FILE *export_file_open(struct export_file *x, const char *path, char *err, size_t errlen);

/* closes and renames into place; 0, or -1 with why in err (the temporary is removed) */
int export_file_commit(struct export_file *x, char *err, size_t errlen);

/* closes and removes the temporary: nothing written */
void export_file_abandon(struct export_file *x);

/*
 * Splits path into its directory (with its trailing '/', or "") and its
 * file name without ext. -1 with why in err when the name does not end
 * in ext or is nothing but ext.
 */
int export_split_path(const char *path, const char *ext, char *dir, size_t dirlen, char *stem,
		      size_t stemlen, char *err, size_t errlen);

#endif

/* export_file.c - exports written whole or not at all */
#include "export/export_file.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <unistd.h>

FILE *
export_fopen(const char *path)
{
	int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
	FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
	if (fd >= 0 && !f)
		close(fd);
	return f;
}

FILE *
export_file_open(struct export_file *x, const char *path, char *err, size_t errlen)
{
	if ((size_t)snprintf(x->path, sizeof x->path, "%s", path) >= sizeof x->path) {
		snprintf(err, errlen, "path too long");
		return NULL;
	}
	snprintf(x->tmp, sizeof x->tmp, "%s.part", path);
	x->f = export_fopen(x->tmp);
	if (!x->f)
		snprintf(err, errlen, "%s: %s", x->tmp, strerror(errno));
	return x->f;
}

int
export_file_commit(struct export_file *x, char *err, size_t errlen)
{
	int bad = ferror(x->f);
	if (fclose(x->f) != 0 || bad) {
		snprintf(err, errlen, "%s: %s", x->path, bad ? "write error" : strerror(errno));
		unlink(x->tmp);
		return -1;
	}
	if (rename(x->tmp, x->path) < 0) {
		snprintf(err, errlen, "%s: %s", x->path, strerror(errno));
		unlink(x->tmp);
		return -1;
	}
	return 0;
}

void
export_file_abandon(struct export_file *x)
{
	fclose(x->f);
	unlink(x->tmp);
}

int
export_split_path(const char *path, const char *ext, char *dir, size_t dirlen, char *stem,
		  size_t stemlen, char *err, size_t errlen)
{
	const char *slash = strrchr(path, '/'), *name = slash ? slash + 1 : path;
	size_t n = strlen(name), e = strlen(ext);
	if (n <= e || strcmp(name + n - e, ext)) {
		snprintf(err, errlen, "'%.60s' must be a file name ending in %s", name, ext);
		return -1;
	}
	if ((size_t)(name - path) >= dirlen || n - e >= stemlen) {
		snprintf(err, errlen, "path too long");
		return -1;
	}
	memcpy(dir, path, (size_t)(name - path));
	dir[name - path] = 0;
	memcpy(stem, name, n - e);
	stem[n - e] = 0;
	return 0;
}

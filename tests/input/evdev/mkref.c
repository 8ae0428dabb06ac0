/*
 * mkref - makes evemu files with libevemu's own writer (evemu_write for the
 * description read with evemu_read, evemu_record for the events, read from
 * a pipe as from a device) and dumps what libevemu's reader makes of a file.
 *   mkref record DESC EVENTS OUT   EVENTS: lines "sec usec type code value"
 *   mkref dump FILE                prints N/I/B/P/A/E lines from libevemu's reader
 */
#include <evemu.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int
record(const char *desc, const char *events, const char *out)
{
	FILE *d = fopen(desc, "r"), *e = fopen(events, "r"), *o = fopen(out, "w");
	struct evemu_device *dev = evemu_new(NULL);
	if (!d || !e || !o || evemu_read(dev, d) <= 0)
		return 1;
	evemu_write(dev, o);
	int fd[2];
	if (pipe(fd))
		return 1;
	unsigned long sec, usec;
	unsigned type, code;
	int value;
	while (fscanf(e, "%lu %lu %x %x %d", &sec, &usec, &type, &code, &value) == 5) {
		struct input_event ev;
		memset(&ev, 0, sizeof ev);
		ev.time.tv_sec = sec;
		ev.time.tv_usec = usec;
		ev.type = type;
		ev.code = code;
		ev.value = value;
		if (write(fd[1], &ev, sizeof ev) != sizeof ev)
			return 1;
	}
	evemu_record(o, fd[0], 100);
	fclose(o);
	evemu_delete(dev);
	return 0;
}

static int
dump(const char *path)
{
	FILE *f = fopen(path, "r");
	struct evemu_device *dev = evemu_new(NULL);
	if (!f || evemu_read(dev, f) <= 0)
		return 1;
	printf("N %s\n", evemu_get_name(dev));
	printf("I %u %u %u %u\n", evemu_get_id_bustype(dev), evemu_get_id_vendor(dev),
	       evemu_get_id_product(dev), evemu_get_id_version(dev));
	for (int p = 0; p <= INPUT_PROP_MAX; p++)
		if (evemu_has_prop(dev, p))
			printf("P %d\n", p);
	/* EV_SYN left out: libevdev reports every SYN code of a device */
	for (int t = 1; t <= EV_MAX; t++)
		for (int c = 0; c <= KEY_MAX; c++)
			if (evemu_has_event(dev, t, c))
				printf("B %d %d\n", t, c);
	for (int c = 0; c <= ABS_MAX; c++)
		if (evemu_has_event(dev, EV_ABS, c))
			printf("A %d %d %d %d %d %d\n", c, evemu_get_abs_minimum(dev, c),
			       evemu_get_abs_maximum(dev, c), evemu_get_abs_fuzz(dev, c),
			       evemu_get_abs_flat(dev, c), evemu_get_abs_resolution(dev, c));
	struct input_event ev;
	while (evemu_read_event(f, &ev) > 0)
		printf("E %lu %lu %u %u %d\n", (unsigned long)ev.time.tv_sec,
		       (unsigned long)ev.time.tv_usec, ev.type, ev.code, ev.value);
	evemu_delete(dev);
	return 0;
}

int
main(int argc, char **argv)
{
	if (argc == 5 && !strcmp(argv[1], "record"))
		return record(argv[2], argv[3], argv[4]);
	if (argc == 3 && !strcmp(argv[1], "dump"))
		return dump(argv[2]);
	fprintf(stderr, "usage: mkref record DESC EVENTS OUT | mkref dump FILE\n");
	return 2;
}

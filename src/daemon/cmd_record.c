/* cmd_record.c - record start|stop, get record: the loop recorded for replay (daemon/tape.h) */
#include <stdio.h>

#include "daemon/cmd_ctx.h"

int
cmd_record_start(struct cmd_ctx *c)
{
	char path[4096], err[4400];
	if (cmd_path(c, c->argv[0], 1, path, sizeof path) < 0)
		return -1;
	if (!c->d->record)
		return cmd_fail(c, "internal", "this daemon cannot record");
	if (c->d->record(c->d, path, err, sizeof err) < 0)
		return cmd_fail(c, "busy", "%s", err);
	json_object_set_new(c->result, "path", json_string(c->argv[0]));
	return 0;
}

int
cmd_record_stop(struct cmd_ctx *c)
{
	const char *dir;
	uint64_t counts[3];
	if (!c->d->recording || !c->d->recording(c->d, &dir, counts))
		return cmd_fail(c, "not-found", "not recording");
	json_object_set_new(c->result, "path", json_string(dir));
	json_object_set_new(c->result, "frames", json_integer((json_int_t)counts[0]));
	json_object_set_new(c->result, "lines", json_integer((json_int_t)counts[1]));
	char err[512];
	if (c->d->record(c->d, NULL, err, sizeof err) < 0)
		return cmd_fail(c, "io", "%s", err);
	return 0;
}

int
cmd_get_record(struct cmd_ctx *c)
{
	const char *dir = NULL;
	uint64_t counts[3] = { 0 };
	int on = c->d->recording && c->d->recording(c->d, &dir, counts);
	json_object_set_new(c->result, "recording", json_boolean(on));
	json_object_set_new(c->result, "path", on ? json_string(dir) : json_null());
	json_object_set_new(c->result, "frames", json_integer((json_int_t)counts[0]));
	json_object_set_new(c->result, "lines", json_integer((json_int_t)counts[1]));
	json_object_set_new(c->result, "waits", json_integer((json_int_t)counts[2]));
	return 0;
}

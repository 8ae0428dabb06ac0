/* sink.c - the generic side of frame sinks (see sink.h) */
#include "draw/sink.h"

#include <stdio.h>

int
sink_frame_check(const struct frame *f, char *err, size_t errlen)
{
	if (!f || !f->rgba) {
		snprintf(err, errlen, "frame: no pixels");
		return -1;
	}
	if (f->width < 1 || f->height < 1 || f->width > SINK_FRAME_SIDE_MAX ||
	    f->height > SINK_FRAME_SIDE_MAX) {
		snprintf(err, errlen, "frame: size %dx%d is out of range (1..%d each way)",
			 f->width, f->height, SINK_FRAME_SIDE_MAX);
		return -1;
	}
	if (f->stride < 4 * f->width) {
		snprintf(err, errlen, "frame: stride %d is less than 4 * width %d", f->stride,
			 f->width);
		return -1;
	}
	return 0;
}

int
sink_write(struct sink *s, const struct frame *f, char *err, size_t errlen)
{
	char tmp[1];
	if (!err || !errlen) {
		err = tmp;
		errlen = sizeof tmp;
	}
	int r = sink_frame_check(f, err, errlen);
	if (r == 0)
		r = s->ops->write(s, f, err, errlen);
	if (r == 0)
		s->frames++;
	else
		s->failures++;
	return r;
}

void
sink_close(struct sink *s)
{
	if (s)
		s->ops->close(s);
}

/*
 * scanout.h - a frame into a screen's memory: centred, cropped when
 * larger, black around it, converted to the screen's pixel format, rows
 * `pitch` bytes apart. What the fbdev and the KMS sinks share.
 */
#ifndef POSTURE_DRAW_SCANOUT_H
#define POSTURE_DRAW_SCANOUT_H

#include <stddef.h>
#include <stdint.h>

#include "draw/frame.h"
#include "draw/pixfmt.h"

/*
 * f into the w x h area at mem (rows pitch bytes apart) in pf, black (one
 * pixel in pf, pf->bytes long) where the frame does not reach.
 */
void scanout_draw(const struct pixfmt *pf, const uint8_t *black, const struct frame *f, uint8_t *mem,
		  size_t pitch, int w, int h);

#endif

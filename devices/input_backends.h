/*
 * input_backends.h - the table of every device backend built in, in the
 * order the device set tries them; the first (evdev) is what `auto` means.
 */
#ifndef POSTURE_DEVICES_INPUT_BACKENDS_H
#define POSTURE_DEVICES_INPUT_BACKENDS_H

#include "devices/input_backend.h"

extern const struct input_backend *const input_backends[];
extern const int input_backends_count;

#endif

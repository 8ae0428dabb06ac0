/* input_backends.c - the backends built in (see input_backends.h) */
#include "devices/input_backends.h"

#include "devices/can_dev.h"
#include "devices/evdev_dev.h"
#include "devices/hidraw_dev.h"
#include "devices/usb_dev.h"

const struct input_backend *const input_backends[] = {
	&input_backend_evdev,
	&input_backend_hidraw,
	&input_backend_usb,
	&input_backend_can,
};

const int input_backends_count = (int)(sizeof input_backends / sizeof input_backends[0]);

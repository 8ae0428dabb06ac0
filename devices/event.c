/* event.c - names of the event kinds */
#include "devices/event.h"

const char *
input_kind_to_str(enum input_kind k)
{
	switch (k) {
	case INPUT_MOTION:
		return "motion";
	case INPUT_POINTER:
		return "pointer";
	case INPUT_BUTTON:
		return "button";
	case INPUT_WHEEL:
		return "wheel";
	case INPUT_KEY:
		return "key";
	case INPUT_VALUATOR:
		return "valuator";
	case INPUT_ADDED:
		return "added";
	case INPUT_REMOVED:
		return "removed";
	case INPUT_FRAME:
		return "frame";
	}
	return "unknown";
}

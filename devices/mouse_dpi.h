/*
 * mouse_dpi.h - a mouse's resolution, from udev's hwdb property MOUSE_DPI
 * (systemd's 70-mouse.hwdb): "DPI[@HZ]" or a list of them with the
 * default setting marked by '*' ("400@125 *800@125 1600@125"). Motion is
 * normalised by it (devices/motion_scale.h), so mice of different
 * resolutions move the pointer alike.
 */
#ifndef POSTURE_DEVICES_MOUSE_DPI_H
#define POSTURE_DEVICES_MOUSE_DPI_H

/*
 * The default DPI of a MOUSE_DPI value: the entry marked '*', or the only
 * one. Returns it, or 0 for a value that is none of these (several entries
 * and no mark, no number, a number out of 1..100000, trailing garbage).
 */
double mouse_dpi_parse(const char *value);

/*
 * The DPI of the device node path (its MOUSE_DPI in the udev database),
 * or INPUT_DEV_DPI_DEFAULT when udev has none or cannot be asked.
 */
double mouse_dpi_of_node(const char *path);

#endif

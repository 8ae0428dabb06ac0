/*
 * menu_draw.h - the pop-up menu's layout (menu.h) into a draw list, over
 * everything in screen space: a dark translucent panel, the filter row on
 * top, group titles dimmer than the commands, the highlighted command on a
 * bright band, "more" markers when the list scrolls, and the highlighted
 * command's usage at the bottom. Text is the renderer's monospaced font
 * (VIEW_CHAR_PX a character), each row's text on its baseline.
 *
 * It lives here, not in src/draw, because the layout is this layer's.
 */
#ifndef POSTURE_INTERACT_MENU_DRAW_H
#define POSTURE_INTERACT_MENU_DRAW_H

#include "draw/view.h"
#include "interact/menu.h"

/* the highlighted command's band (opaque, so a picture shows it exactly) */
#define MENU_DRAW_HIGHLIGHT_RGBA { 52, 112, 196, 255 }
/* the panel: dark and translucent, as the status line's band */
#define MENU_DRAW_PANEL_RGBA { 20, 24, 32, 225 }

/*
 * Appends the menu's panel, bands, lines and one text per row to dl; a
 * closed layout adds nothing. What does not fit in dl is dropped and
 * counted there (dl->dropped).
 */
void menu_draw(struct drawlist *dl, const struct menu_layout *L);

#endif

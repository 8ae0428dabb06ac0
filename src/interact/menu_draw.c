/* menu_draw.c - the pop-up menu into a draw list (see menu_draw.h) */
#include "interact/menu_draw.h"

static const uint8_t c_panel[4] = MENU_DRAW_PANEL_RGBA;
static const uint8_t c_highlight[4] = MENU_DRAW_HIGHLIGHT_RGBA;
static const uint8_t c_filter_band[4] = { 44, 50, 66, 235 };
static const uint8_t c_edge[4] = { 255, 255, 255, 90 };
static const uint8_t c_item[4] = { 235, 238, 242, 255 };
static const uint8_t c_item_hi[4] = { 255, 255, 255, 255 };
static const uint8_t c_title[4] = { 150, 160, 178, 255 };
static const uint8_t c_more[4] = { 130, 140, 158, 255 };
static const uint8_t c_filter[4] = { 200, 220, 255, 255 };
static const uint8_t c_hint[4] = { 255, 236, 170, 255 };

/* a horizontal line across the panel at pixel row y */
static void
hline(struct drawlist *dl, const struct menu_layout *L, double y)
{
	double a[3] = { L->x0, y + 0.5, 0 }, b[3] = { L->x1, y + 0.5, 0 };
	view_line(dl, a, b, c_edge);
}

/* the panel's outline, the filter's and the hint's separators */
static void
panel_lines(struct drawlist *dl, const struct menu_layout *L)
{
	double x0 = L->x0 + 0.5, x1 = L->x1 - 0.5, y0 = L->y0 + 0.5, y1 = L->y1 - 0.5;
	double c[4][3] = { { x0, y0, 0 }, { x1, y0, 0 }, { x1, y1, 0 }, { x0, y1, 0 } };
	view_batch_begin(dl, VIEW_LINES, VIEW_SCREEN, 1, 0);
	for (int i = 0; i < 4; i++)
		view_line(dl, c[i], c[(i + 1) % 4], c_edge);
	for (int i = 0; i < L->nrows; i++) {
		if (L->row[i].kind == MENU_ROW_FILTER)
			hline(dl, L, L->row[i].y1);
		else if (L->row[i].kind == MENU_ROW_HINT)
			hline(dl, L, L->row[i].y0 - 1);
	}
}

static const uint8_t *
text_colour(const struct menu_layout_row *row)
{
	switch (row->kind) {
	case MENU_ROW_FILTER:
		return c_filter;
	case MENU_ROW_TITLE:
		return c_title;
	case MENU_ROW_ITEM:
		return row->highlighted ? c_item_hi : c_item;
	case MENU_ROW_MORE_UP:
	case MENU_ROW_MORE_DOWN:
		return c_more;
	case MENU_ROW_HINT:
		return c_hint;
	}
	return c_item;
}

void
menu_draw(struct drawlist *dl, const struct menu_layout *L)
{
	if (!L->open)
		return;
	/* bands first: the renderer draws text over every band */
	view_add_rect(dl, L->x0, L->y0, L->x1, L->y1, c_panel);
	for (int i = 0; i < L->nrows; i++) {
		const struct menu_layout_row *row = &L->row[i];
		if (row->kind == MENU_ROW_FILTER)
			view_add_rect(dl, row->x0, row->y0, row->x1, row->y1, c_filter_band);
		else if (row->highlighted)
			view_add_rect(dl, row->x0 + 2, row->y0, row->x1 - 2, row->y1, c_highlight);
	}
	panel_lines(dl, L);
	/* the baseline as the status line has it: 5 px above the row's bottom */
	for (int i = 0; i < L->nrows; i++) {
		const struct menu_layout_row *row = &L->row[i];
		if (row->text[0])
			view_add_text(dl, row->x0 + L->pad_px, row->y1 - 5, row->text, text_colour(row),
				      VIEW_ALIGN_LEFT);
	}
}

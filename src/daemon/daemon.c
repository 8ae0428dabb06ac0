/* daemon.c - undo and redo checkpoints */
#include "daemon/daemon.h"

#include <stdlib.h>
#include <string.h>

void
daemon_checkpoints_clear(struct checkpoints *c)
{
	for (int i = 0; i < c->n; i++)
		free(c->text[i]);
	c->n = 0;
}

void
daemon_checkpoints_push(struct checkpoints *c, char *text, size_t len)
{
	if (c->n == DAEMON_UNDO_MAX) { /* forget the oldest */
		free(c->text[0]);
		memmove(c->text, c->text + 1, sizeof *c->text * (DAEMON_UNDO_MAX - 1));
		memmove(c->len, c->len + 1, sizeof *c->len * (DAEMON_UNDO_MAX - 1));
		c->n--;
	}
	c->text[c->n] = text;
	c->len[c->n] = len;
	c->n++;
}

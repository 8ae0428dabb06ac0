/*
 * hid_desc.c - the HID report descriptor parser (see hid_desc.h). The
 * rules follow drivers/hid/hid-core.c: fetch_item, hid_parser_main,
 * hid_parser_global, hid_parser_local, hid_add_field and
 * hid_setup_resolution_multiplier; the comments name the kernel's step
 * each block stands for.
 */
#include "devices/hid_desc.h"

#include <stdarg.h>
#include <string.h>

enum item_type { ITEM_MAIN = 0, ITEM_GLOBAL = 1, ITEM_LOCAL = 2, ITEM_RESERVED = 3 };

enum report_type { REPORT_INPUT, REPORT_OUTPUT, REPORT_FEATURE, REPORT_TYPES };

/* HID 1.11 6.2.2.4 main item tags */
#define TAG_INPUT 0x8
#define TAG_OUTPUT 0x9
#define TAG_COLLECTION 0xa
#define TAG_FEATURE 0xb
#define TAG_END_COLLECTION 0xc

/* 6.2.2.7 global item tags */
#define TAG_USAGE_PAGE 0x0
#define TAG_LOGICAL_MIN 0x1
#define TAG_LOGICAL_MAX 0x2
#define TAG_PHYSICAL_MIN 0x3
#define TAG_PHYSICAL_MAX 0x4
#define TAG_UNIT_EXPONENT 0x5
#define TAG_UNIT 0x6
#define TAG_REPORT_SIZE 0x7
#define TAG_REPORT_ID 0x8
#define TAG_REPORT_COUNT 0x9
#define TAG_PUSH 0xa
#define TAG_POP 0xb

/* 6.2.2.8 local item tags */
#define TAG_USAGE 0x0
#define TAG_USAGE_MIN 0x1
#define TAG_USAGE_MAX 0x2
#define TAG_DELIMITER 0xa

#define TAG_LONG 0xf

struct item {
	unsigned type, tag, size; /* size: data bytes, 0, 1, 2 or 4 for short items */
	uint32_t data;            /* little-endian, zero-extended */
	int is_long;
};

/* the global state Push and Pop save and restore */
struct global {
	uint32_t usage_page;
	int32_t logical_min, logical_max;
	int32_t physical_min, physical_max;
	uint32_t report_size, report_count, report_id;
};

struct parser {
	struct hid_desc *d;
	struct global g;
	struct global stack[HID_DESC_STACK];
	unsigned sp;
	uint16_t open[HID_DESC_MAX_DEPTH]; /* indices of the open collections */
	unsigned depth;
	/* local state: its runs sit at d->runs[run0 .. d->nruns) */
	unsigned run0;
	uint32_t usage_index, usage_min;
	unsigned delimiter_depth, delimiter_branch;
	uint8_t extended[HID_DESC_MAX_RUNS]; /* the run came from a 4-byte item */
	uint32_t bits[REPORT_TYPES][256];    /* report lengths so far */
	size_t at;                           /* offset of the item being parsed */
	char *err;
	size_t errlen;
};

static int
fail(struct parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int
fail(struct parser *p, const char *fmt, ...)
{
	if (p->errlen == 0)
		return -1;
	int k = snprintf(p->err, p->errlen, "byte %zu: ", p->at);
	if (k < 0 || (size_t)k >= p->errlen)
		return -1;
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(p->err + k, p->errlen - (size_t)k, fmt, ap);
	va_end(ap);
	return -1;
}

static uint32_t
item_udata(const struct item *it)
{
	return it->data;
}

static int32_t
item_sdata(const struct item *it)
{
	switch (it->size) {
	case 1:
		return (int8_t)it->data;
	case 2:
		return (int16_t)it->data;
	case 4:
		return (int32_t)it->data;
	}
	return 0;
}

/* fetch_item: one item at bytes[*pos], or -1 when the bytes run out */
static int
fetch_item(struct parser *p, const uint8_t *bytes, size_t n, size_t *pos, struct item *dest)
{
	size_t at = *pos;
	uint8_t b = bytes[at++];
	memset(dest, 0, sizeof *dest);
	dest->type = (b >> 2) & 3;
	dest->tag = (b >> 4) & 15;

	/* long item: a size byte, a tag byte, then the data (skipped) */
	if (dest->tag == TAG_LONG) {
		dest->is_long = 1;
		if (n - at < 2)
			return fail(p, "long item 0x%02x truncated: a 2-byte header, %zu left", b,
				    n - at);
		unsigned size = bytes[at];
		at += 2;
		if (n - at < size)
			return fail(p, "long item truncated: %u data bytes, %zu left", size,
				    n - at);
		*pos = at + size;
		return 0;
	}

	/* short item: 0, 1, 2 or 4 data bytes */
	unsigned size = b & 3;
	if (size == 3)
		size = 4;
	if (n - at < size)
		return fail(p, "item 0x%02x truncated: %u data bytes, %zu left", b, size, n - at);
	dest->size = size;
	for (unsigned i = 0; i < size; i++)
		dest->data |= (uint32_t)bytes[at + i] << (8 * i);
	*pos = at + size;
	return 0;
}

/* hid_lookup_collection: the usage of the nearest open collection of a type */
static uint32_t
lookup_collection(const struct parser *p, unsigned type)
{
	for (unsigned i = p->depth; i-- > 0;) {
		const struct hid_desc_collection *c = &p->d->collections[p->open[i]];
		if (c->type == type)
			return c->usage;
	}
	return 0;
}

static void
reset_local(struct parser *p)
{
	p->d->nruns = p->run0;
	p->usage_index = 0;
	p->usage_min = 0;
	p->delimiter_depth = 0;
	p->delimiter_branch = 0;
}

/* hid_add_usage for n consecutive usages; size: the bytes of the item */
static int
add_usages(struct parser *p, uint32_t first, uint32_t count, unsigned size)
{
	struct hid_desc *d = p->d;
	if (count == 0)
		return 0;
	if (p->usage_index + count > HID_DESC_MAX_USAGES)
		return fail(p, "more than %d usages before one main item", HID_DESC_MAX_USAGES);
	if (d->nruns == HID_DESC_MAX_RUNS)
		return fail(p, "more than %d usage items", HID_DESC_MAX_RUNS);
	/* complete_usage: a 1- or 2-byte usage takes the current page */
	if (size <= 2)
		first = (first & 0xffff) | (p->g.usage_page & 0xffff) << 16;
	p->extended[d->nruns] = size > 2;
	d->runs[d->nruns].first = first;
	d->runs[d->nruns].count = count;
	d->nruns++;
	p->usage_index += count;
	return 0;
}

/* hid_concatenate_last_usage_page: the last page applies to usages before it */
static void
concatenate_last_usage_page(struct parser *p)
{
	uint32_t page = p->g.usage_page & 0xffff;
	for (unsigned i = p->d->nruns; i-- > p->run0;) {
		struct hid_desc_run *r = &p->d->runs[i];
		if (p->extended[i])
			continue;
		if (r->first >> 16 == page)
			break;
		r->first = (r->first & 0xffff) | page << 16;
	}
}

static int
open_collection(struct parser *p, unsigned type)
{
	struct hid_desc *d = p->d;
	if (p->depth == HID_DESC_MAX_DEPTH)
		return fail(p, "collections nested deeper than %d", HID_DESC_MAX_DEPTH);
	if (d->ncollections == HID_DESC_MAX_COLLECTIONS)
		return fail(p, "more than %d collections", HID_DESC_MAX_COLLECTIONS);
	struct hid_desc_collection *c = &d->collections[d->ncollections];
	c->usage = d->nruns > p->run0 ? d->runs[p->run0].first : 0;
	c->type = (uint8_t)type;
	c->depth = (uint8_t)p->depth;
	c->parent = p->depth ? p->open[p->depth - 1] : HID_DESC_NONE;
	p->open[p->depth++] = (uint16_t)d->ncollections++;
	return 0;
}

/* the input report with this id, registered on first use */
static int
input_report(struct parser *p, unsigned id, unsigned *dest)
{
	struct hid_desc *d = p->d;
	if (d->report_index[id] == 0xff) {
		if (d->nreports == HID_DESC_MAX_REPORTS)
			return fail(p, "more than %d input reports", HID_DESC_MAX_REPORTS);
		d->report_index[id] = (uint8_t)d->nreports;
		memset(&d->reports[d->nreports], 0, sizeof d->reports[0]);
		d->reports[d->nreports].id = (uint8_t)id;
		d->nreports++;
	}
	*dest = d->report_index[id];
	return 0;
}

static int
has_usage(const struct parser *p, uint32_t usage)
{
	for (unsigned i = p->run0; i < p->d->nruns; i++) {
		const struct hid_desc_run *r = &p->d->runs[i];
		if (usage >= r->first && usage - r->first < r->count)
			return 1;
	}
	return 0;
}

/* hid_add_field: a main Input, Output or Feature item */
static int
add_field(struct parser *p, enum report_type type, uint32_t flags)
{
	struct hid_desc *d = p->d;
	const struct global *g = &p->g;
	unsigned id = g->report_id;
	unsigned report = HID_DESC_NONE;

	if (type == REPORT_INPUT && input_report(p, id, &report) < 0)
		return -1;

	/* the logical range, signed or unsigned as the minimum says */
	if ((g->logical_min < 0 && g->logical_max < g->logical_min) ||
	    (g->logical_min >= 0 && (uint32_t)g->logical_max < (uint32_t)g->logical_min))
		return fail(p, "Logical Maximum %d below Logical Minimum %d", g->logical_max,
			    g->logical_min);

	/* the report grows by size * count bits */
	uint32_t offset = p->bits[type][id];
	uint32_t bits = g->report_size * g->report_count;
	uint32_t limit = type == REPORT_INPUT ? HID_DESC_MAX_REPORT_BITS : HID_DESC_MAX_OTHER_BITS;
	if (bits > limit - offset)
		return fail(p, "%s report %u longer than %u bits",
			    type == REPORT_INPUT    ? "input"
			    : type == REPORT_OUTPUT ? "output"
						    : "feature",
			    id, limit);
	p->bits[type][id] = offset + bits;

	int data = p->usage_index > 0 && !(flags & HID_FIELD_CONSTANT) && g->report_count > 0;

	/* a feature holding a Resolution Multiplier is kept for the wheels */
	if (type == REPORT_FEATURE && g->report_count > 0 &&
	    has_usage(p, HID_USAGE_GD_RESOLUTION_MULTIPLIER)) {
		if (d->nmultipliers == HID_DESC_MAX_MULTIPLIERS)
			return fail(p, "more than %d Resolution Multipliers",
				    HID_DESC_MAX_MULTIPLIERS);
		if (g->report_size == 0 || g->report_size > 32)
			return fail(p, "Resolution Multiplier of %u bits (1 to 32 supported)",
				    g->report_size);
		struct hid_desc_multiplier *m = &d->multipliers[d->nmultipliers++];
		m->report_id = (uint8_t)id;
		m->bit_offset = (uint16_t)offset;
		m->size = (uint16_t)g->report_size;
		m->logical_max = g->logical_max;
		/*
		 * hid_calculate_multiplier with the value hid-input sets (the
		 * logical maximum): (v - lmin) / (lmax - lmin) * (pmax - pmin) + pmin
		 */
		int64_t lmin = g->logical_min, lmax = g->logical_max;
		int64_t pmin = g->physical_min, pmax = g->physical_max;
		int64_t eff = 1;
		if (lmax != lmin) {
			eff = (lmax - lmin) / (lmax - lmin) * (pmax - pmin) + pmin;
			if (eff == 0 || eff > 255 || eff < -255)
				eff = 1;
		}
		m->effective = (int32_t)eff;
		m->collection = p->depth ? p->open[p->depth - 1] : HID_DESC_NONE;
	}

	if (type != REPORT_INPUT)
		return 0;

	/* input fields are kept, padding included, for the decoder and describe */
	if (d->nfields == HID_DESC_MAX_FIELDS)
		return fail(p, "more than %d input fields", HID_DESC_MAX_FIELDS);
	if (data && (g->report_size == 0 || g->report_size > 32))
		return fail(p, "input field of %u-bit values (1 to 32 supported)", g->report_size);
	if (data && !(flags & HID_FIELD_VARIABLE) && g->report_count > HID_DESC_MAX_ARRAY)
		return fail(p, "array field of %u values (at most %d)", g->report_count,
			    HID_DESC_MAX_ARRAY);
	if (data && d->nvalues + g->report_count > HID_DESC_MAX_VALUES)
		return fail(p, "more than %d input values", HID_DESC_MAX_VALUES);

	struct hid_desc_field *f = &d->fields[d->nfields++];
	memset(f, 0, sizeof *f);
	f->report = (uint16_t)report;
	f->bit_offset = (uint16_t)offset;
	f->size = (uint16_t)g->report_size;
	f->count = (uint16_t)g->report_count;
	f->flags = flags;
	f->logical_min = g->logical_min;
	f->logical_max = g->logical_max;
	f->physical_min = g->physical_min;
	f->physical_max = g->physical_max;
	f->application = lookup_collection(p, HID_COLLECTION_APPLICATION);
	f->physical = lookup_collection(p, HID_COLLECTION_PHYSICAL);
	f->logical = lookup_collection(p, HID_COLLECTION_LOGICAL);
	f->collection = p->depth ? p->open[p->depth - 1] : HID_DESC_NONE;
	f->run_first = (uint16_t)p->run0;
	f->run_count = (uint16_t)(d->nruns - p->run0);
	f->usages = p->usage_index;
	f->value_first = HID_DESC_NONE;
	f->resolution_multiplier = 1;
	if (data)
		d->nvalues += g->report_count;

	/* the runs now belong to the field */
	p->run0 = d->nruns;
	return 0;
}

static int
parse_main(struct parser *p, const struct item *it)
{
	int ret = 0;
	concatenate_last_usage_page(p);
	uint32_t data = item_udata(it);
	switch (it->tag) {
	case TAG_COLLECTION:
		ret = open_collection(p, data & 0xff);
		break;
	case TAG_END_COLLECTION:
		if (p->depth == 0)
			ret = fail(p, "End Collection without Collection");
		else
			p->depth--;
		break;
	case TAG_INPUT:
		ret = add_field(p, REPORT_INPUT, data);
		break;
	case TAG_OUTPUT:
		ret = add_field(p, REPORT_OUTPUT, data);
		break;
	case TAG_FEATURE:
		ret = add_field(p, REPORT_FEATURE, data);
		break;
	default:
		/* the kernel warns and goes on */
		break;
	}
	reset_local(p);
	return ret;
}

static int
parse_global(struct parser *p, const struct item *it)
{
	struct global *g = &p->g;
	switch (it->tag) {
	case TAG_PUSH:
		if (p->sp == HID_DESC_STACK)
			return fail(p, "Push nested deeper than %d", HID_DESC_STACK);
		p->stack[p->sp++] = *g;
		return 0;
	case TAG_POP:
		if (p->sp == 0)
			return fail(p, "Pop without Push");
		*g = p->stack[--p->sp];
		return 0;
	case TAG_USAGE_PAGE:
		g->usage_page = item_udata(it);
		return 0;
	case TAG_LOGICAL_MIN:
		g->logical_min = item_sdata(it);
		return 0;
	case TAG_LOGICAL_MAX:
		if (g->logical_min < 0)
			g->logical_max = item_sdata(it);
		else
			g->logical_max = (int32_t)item_udata(it);
		return 0;
	case TAG_PHYSICAL_MIN:
		g->physical_min = item_sdata(it);
		return 0;
	case TAG_PHYSICAL_MAX:
		if (g->physical_min < 0)
			g->physical_max = item_sdata(it);
		else
			g->physical_max = (int32_t)item_udata(it);
		return 0;
	case TAG_UNIT_EXPONENT:
	case TAG_UNIT:
		return 0;
	case TAG_REPORT_SIZE:
		g->report_size = item_udata(it);
		if (g->report_size > HID_DESC_MAX_SIZE)
			return fail(p, "Report Size %u over %d", g->report_size, HID_DESC_MAX_SIZE);
		return 0;
	case TAG_REPORT_COUNT:
		g->report_count = item_udata(it);
		if (g->report_count > HID_DESC_MAX_COUNT)
			return fail(p, "Report Count %u over %d", g->report_count,
				    HID_DESC_MAX_COUNT);
		return 0;
	case TAG_REPORT_ID:
		g->report_id = item_udata(it);
		if (g->report_id == 0 || g->report_id > 255)
			return fail(p, "Report ID %u outside 1-255", g->report_id);
		return 0;
	}
	return fail(p, "unknown global item tag 0x%x", it->tag);
}

static int
parse_local(struct parser *p, const struct item *it)
{
	uint32_t data = item_udata(it);
	switch (it->tag) {
	case TAG_DELIMITER:
		if (data) {
			if (p->delimiter_depth != 0)
				return fail(p, "nested Delimiter");
			p->delimiter_depth++;
			p->delimiter_branch++;
		} else {
			if (p->delimiter_depth < 1)
				return fail(p, "Delimiter close without open");
			p->delimiter_depth--;
		}
		return 0;
	case TAG_USAGE:
		/* alternative usages after the first delimited set are ignored */
		if (p->delimiter_branch > 1)
			return 0;
		return add_usages(p, data, 1, it->size);
	case TAG_USAGE_MIN:
		if (p->delimiter_branch > 1)
			return 0;
		p->usage_min = data;
		return 0;
	case TAG_USAGE_MAX: {
		if (p->delimiter_branch > 1)
			return 0;
		if (data < p->usage_min)
			return fail(p, "Usage Minimum 0x%x above Usage Maximum 0x%x", p->usage_min,
				    data);
		/* a range past the usage bound is cut short, as the kernel does */
		uint64_t count = (uint64_t)data - p->usage_min + 1;
		if (count + p->usage_index > HID_DESC_MAX_USAGES) {
			if (p->usage_index >= HID_DESC_MAX_USAGES)
				return fail(p, "more than %d usages before one main item",
					    HID_DESC_MAX_USAGES);
			count = HID_DESC_MAX_USAGES - p->usage_index;
		}
		return add_usages(p, p->usage_min, (uint32_t)count, it->size);
	}
	}
	/* unknown local items are ignored */
	return 0;
}

/* fields grouped by report, in descriptor order within each */
static void
group_fields(struct hid_desc *d)
{
	static const struct hid_desc_field zero;
	struct hid_desc_field tmp[HID_DESC_MAX_FIELDS];
	unsigned k = 0;
	for (unsigned r = 0; r < d->nreports; r++) {
		d->reports[r].field_first = (uint16_t)k;
		for (unsigned i = 0; i < d->nfields; i++)
			if (d->fields[i].report == r)
				tmp[k++] = d->fields[i];
		d->reports[r].field_count = (uint16_t)(k - d->reports[r].field_first);
	}
	for (unsigned i = 0; i < k; i++)
		d->fields[i] = tmp[i];
	for (unsigned i = k; i < HID_DESC_MAX_FIELDS; i++)
		d->fields[i] = zero;
}

/*
 * hid_apply_multiplier: a multiplier governs the input fields inside its
 * nearest Logical collection (the top-level one if none; then, as the
 * kernel has it, nothing)
 */
static void
apply_multiplier(struct hid_desc *d, uint16_t where, int32_t effective)
{
	if (where == HID_DESC_NONE)
		return;
	uint16_t mc = where;
	while (d->collections[mc].parent != HID_DESC_NONE &&
	       d->collections[mc].type != HID_COLLECTION_LOGICAL)
		mc = d->collections[mc].parent;
	for (unsigned i = 0; i < d->nfields; i++) {
		struct hid_desc_field *f = &d->fields[i];
		uint16_t c = f->collection;
		if (c == HID_DESC_NONE)
			continue;
		while (d->collections[c].parent != HID_DESC_NONE && c != mc)
			c = d->collections[c].parent;
		if (d->collections[c].parent != HID_DESC_NONE)
			f->resolution_multiplier = (int16_t)effective;
	}
}

void
hid_desc_apply_multipliers(struct hid_desc *d)
{
	for (unsigned i = 0; i < d->nfields; i++)
		d->fields[i].resolution_multiplier = 1;
	/* hid_setup_resolution_multiplier: later multipliers override earlier */
	for (unsigned m = 0; m < d->nmultipliers; m++)
		apply_multiplier(d, d->multipliers[m].collection, d->multipliers[m].effective);
}

static void
empty(struct hid_desc *d)
{
	memset(d, 0, sizeof *d);
	memset(d->report_index, 0xff, sizeof d->report_index);
}

int
hid_desc_parse(const uint8_t *bytes, size_t n, struct hid_desc *dest, char *err, size_t errlen)
{
	struct parser p;
	memset(&p, 0, sizeof p);
	p.d = dest;
	p.err = err;
	p.errlen = errlen;
	if (errlen)
		err[0] = '\0';
	empty(dest);

	if (n == 0) {
		fail(&p, "empty descriptor");
		return -1;
	}
	if (n > HID_DESC_MAX_BYTES) {
		p.at = HID_DESC_MAX_BYTES;
		fail(&p, "descriptor longer than %d bytes", HID_DESC_MAX_BYTES);
		return -1;
	}

	/* items one by one, each dispatched by type */
	size_t pos = 0;
	while (pos < n) {
		struct item it;
		p.at = pos;
		if (fetch_item(&p, bytes, n, &pos, &it) < 0)
			goto bad;
		if (it.is_long)
			continue;
		int ret = 0;
		switch ((enum item_type)it.type) {
		case ITEM_MAIN:
			ret = parse_main(&p, &it);
			break;
		case ITEM_GLOBAL:
			ret = parse_global(&p, &it);
			break;
		case ITEM_LOCAL:
			ret = parse_local(&p, &it);
			break;
		case ITEM_RESERVED:
			break;
		}
		if (ret < 0)
			goto bad;
	}

	/* everything opened is closed */
	p.at = n;
	if (p.depth) {
		fail(&p, "%u Collection%s not closed at the end", p.depth, p.depth > 1 ? "s" : "");
		goto bad;
	}
	if (p.delimiter_depth) {
		fail(&p, "Delimiter not closed at the end");
		goto bad;
	}

	/* reports: lengths, ids, their fields and value slots */
	for (unsigned r = 0; r < dest->nreports; r++)
		if (dest->reports[r].id != 0)
			dest->numbered = 1;
	for (unsigned r = 0; r < dest->nreports; r++) {
		struct hid_desc_report *rep = &dest->reports[r];
		rep->bits = (uint16_t)p.bits[REPORT_INPUT][rep->id];
		rep->bytes = (uint16_t)((rep->bits + 7) / 8 + (dest->numbered ? 1 : 0));
	}
	group_fields(dest);
	unsigned v = 0;
	for (unsigned i = 0; i < dest->nfields; i++) {
		struct hid_desc_field *f = &dest->fields[i];
		if (f->usages > 0 && !(f->flags & HID_FIELD_CONSTANT) && f->count > 0) {
			f->value_first = (uint16_t)v;
			v += f->count;
		}
	}
	for (unsigned m = 0; m < dest->nmultipliers; m++)
		dest->multipliers[m].report_bits =
			p.bits[REPORT_FEATURE][dest->multipliers[m].report_id];
	hid_desc_apply_multipliers(dest);
	return 0;

bad:
	empty(dest);
	return -1;
}

/* HID 1.11 Appendix B.2: the boot mouse (buttons 1-3, X, Y) */
static const uint8_t boot_mouse[] = {
	0x05, 0x01, 0x09, 0x02, 0xa1, 0x01, 0x09, 0x01, 0xa1, 0x00, 0x05, 0x09, 0x19, 0x01,
	0x29, 0x03, 0x15, 0x00, 0x25, 0x01, 0x95, 0x03, 0x75, 0x01, 0x81, 0x02, 0x95, 0x01,
	0x75, 0x05, 0x81, 0x01, 0x05, 0x01, 0x09, 0x30, 0x09, 0x31, 0x15, 0x81, 0x25, 0x7f,
	0x75, 0x08, 0x95, 0x02, 0x81, 0x06, 0xc0, 0xc0,
};

/* HID 1.11 Appendix B.1: the boot keyboard (modifiers, reserved, 6 keys; LEDs out) */
static const uint8_t boot_keyboard[] = {
	0x05, 0x01, 0x09, 0x06, 0xa1, 0x01, 0x05, 0x07, 0x19, 0xe0, 0x29, 0xe7, 0x15, 0x00,
	0x25, 0x01, 0x75, 0x01, 0x95, 0x08, 0x81, 0x02, 0x95, 0x01, 0x75, 0x08, 0x81, 0x01,
	0x95, 0x05, 0x75, 0x01, 0x05, 0x08, 0x19, 0x01, 0x29, 0x05, 0x91, 0x02, 0x95, 0x01,
	0x75, 0x03, 0x91, 0x01, 0x95, 0x06, 0x75, 0x08, 0x15, 0x00, 0x25, 0x65, 0x05, 0x07,
	0x19, 0x00, 0x29, 0x65, 0x81, 0x00, 0xc0,
};

const uint8_t *
hid_desc_boot_bytes(enum hid_boot kind, size_t *n)
{
	switch (kind) {
	case HID_BOOT_MOUSE:
		*n = sizeof boot_mouse;
		return boot_mouse;
	case HID_BOOT_KEYBOARD:
		*n = sizeof boot_keyboard;
		return boot_keyboard;
	}
	*n = 0;
	return NULL;
}

int
hid_desc_boot(enum hid_boot kind, struct hid_desc *dest)
{
	size_t n;
	const uint8_t *b = hid_desc_boot_bytes(kind, &n);
	char err[16];
	if (!b) {
		empty(dest);
		return -1;
	}
	return hid_desc_parse(b, n, dest, err, sizeof err);
}

uint32_t
hid_desc_usage(const struct hid_desc *d, const struct hid_desc_field *f, uint32_t i)
{
	if (f->usages == 0)
		return 0;
	if (i >= f->usages)
		i = f->usages - 1;
	for (unsigned k = 0; k < f->run_count; k++) {
		const struct hid_desc_run *r = &d->runs[f->run_first + k];
		if (i < r->count)
			return r->first + i;
		i -= r->count;
	}
	return 0;
}

const struct hid_desc_report *
hid_desc_report_by_id(const struct hid_desc *d, unsigned id)
{
	if (id > 255 || d->report_index[id] == 0xff)
		return NULL;
	return &d->reports[d->report_index[id]];
}

const char *
hid_desc_usage_name(uint32_t usage)
{
	static const struct {
		uint32_t usage;
		const char *name;
	} names[] = {
		{ HID_USAGE_GD_POINTER, "Pointer" },
		{ HID_USAGE_GD_MOUSE, "Mouse" },
		{ HID_USAGE_GD_JOYSTICK, "Joystick" },
		{ HID_USAGE_GD_GAMEPAD, "Gamepad" },
		{ HID_USAGE_GD_KEYBOARD, "Keyboard" },
		{ 0x00010007, "Keypad" },
		{ HID_USAGE_GD_X, "X" },
		{ HID_USAGE_GD_Y, "Y" },
		{ 0x00010032, "Z" },
		{ 0x00010033, "Rx" },
		{ 0x00010034, "Ry" },
		{ 0x00010035, "Rz" },
		{ 0x00010036, "Slider" },
		{ 0x00010037, "Dial" },
		{ HID_USAGE_GD_WHEEL, "Wheel" },
		{ 0x00010039, "Hat switch" },
		{ HID_USAGE_GD_RESOLUTION_MULTIPLIER, "Resolution Multiplier" },
		{ 0x000c0001, "Consumer Control" },
		{ HID_USAGE_CONSUMER_AC_PAN, "AC Pan" },
	};
	for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
		if (names[i].usage == usage)
			return names[i].name;
	return NULL;
}

static void
describe_usage(uint32_t usage, FILE *out)
{
	char buf[32];
	const char *name = hid_desc_usage_name(usage);
	if (!name && usage >> 16 == HID_PAGE_BUTTON) {
		snprintf(buf, sizeof buf, "Button %u", usage & 0xffff);
		name = buf;
	}
	fprintf(out, "0x%04x:0x%04x", usage >> 16, usage & 0xffff);
	if (name)
		fprintf(out, " (%s)", name);
}

void
hid_desc_describe(const struct hid_desc *d, FILE *out)
{
	fprintf(out, "%u input report%s%s\n", d->nreports, d->nreports == 1 ? "" : "s",
		d->numbered ? ", numbered" : "");
	for (unsigned r = 0; r < d->nreports; r++) {
		const struct hid_desc_report *rep = &d->reports[r];
		const char *fmt = d->numbered ? "report %u: %u bytes: the id, then %u bits "
						"(bit 0 follows the id)\n"
					      : "report %u: %u bytes (%u bits)\n";
		fprintf(out, fmt, rep->id, rep->bytes, rep->bits);
		for (unsigned k = 0; k < rep->field_count; k++) {
			const struct hid_desc_field *f = &d->fields[rep->field_first + k];
			const char *kind = f->flags & HID_FIELD_CONSTANT ? "constant"
					   : f->usages == 0		 ? "padding"
					   : f->flags & HID_FIELD_VARIABLE ? "variable"
									   : "array";
			fprintf(out, "  bit %u: %u x %u bits, %s%s, logical %d..%d", f->bit_offset,
				f->count, f->size, kind,
				f->flags & HID_FIELD_RELATIVE ? " relative" : "", f->logical_min,
				f->logical_max);
			if (f->resolution_multiplier != 1)
				fprintf(out, ", resolution x%d", f->resolution_multiplier);
			for (unsigned i = 0; i < f->run_count; i++) {
				const struct hid_desc_run *run = &d->runs[f->run_first + i];
				fputs(i ? ", " : ", usages ", out);
				describe_usage(run->first, out);
				if (run->count > 1) {
					fputs(" .. ", out);
					describe_usage(run->first + run->count - 1, out);
				}
			}
			fputc('\n', out);
		}
	}
}

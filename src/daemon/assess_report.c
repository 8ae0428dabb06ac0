/* assess_report.c - a posture's assessment as a one-page HTML report (see assess_report.h) */
#include "daemon/assess_report.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "assess/assess_tint.h"
#include "daemon/assess_json.h"
#include "daemon/tint.h"
#include "export/export_file.h"
#include "export/html.h"

/* what the report says of each method besides its derivation */
struct method_text {
	const char *title;
	const char *cite;   /* the method's paper */
	const char *tables; /* where its bands and tables come from, and the choices made */
	int nlevels;
	struct {
		int level;
		const char *scores;
		const char *words;
	} levels[5];
};

static const struct method_text methods[ASSESS_NMETHODS] = {
	[ASSESS_RULA] = {
		"RULA",
		"McAtamney L, Corlett EN. RULA: a survey method for the investigation of work-related "
		"upper limb disorders. Applied Ergonomics 24(2):91-99, 1993. "
		"doi:10.1016/0003-6870(93)90080-S.",
		"Neck, trunk, legs and force/load bands from the paper's text; arm and wrist bands "
		"from the ErgoPlus RULA worksheet. Tables A, B, C agree cell for cell across the "
		"worksheet and open implementations but for Table A upper arm 6, lower arm 2, wrist 1, "
		"twist 1, read 7 in one worksheet copy and 8 everywhere else: 8 is used. Score C is "
		"read at 8 and score D at 7 when higher.",
		4,
		{ { 1, "1-2", "acceptable if not maintained or repeated for long periods" },
		  { 2, "3-4", "further investigation needed; changes may be required" },
		  { 3, "5-6", "investigation and changes required soon" },
		  { 4, "7", "investigation and changes required immediately" } },
	},
	[ASSESS_REBA] = {
		"REBA",
		"Hignett S, McAtamney L. Rapid Entire Body Assessment (REBA). Applied Ergonomics "
		"31(2):201-205, 2000.",
		"Bands and adjustments from Hignett & McAtamney's chapter (Marras & Karwowski, "
		"Table 42.2) and the REBA worksheets; Tables A, B, C identical in the worksheet and "
		"open implementations (Table A: rows trunk, columns neck then legs). The worksheet's "
		"-1 for the third activity item is a typo: +1 is used.",
		5,
		{ { 0, "1", "negligible risk: none necessary" },
		  { 1, "2-3", "low risk: may be necessary" },
		  { 2, "4-7", "medium risk: necessary" },
		  { 3, "8-10", "high risk: necessary soon" },
		  { 4, "11-15", "very high risk: necessary now" } },
	},
	[ASSESS_OWAS] = {
		"OWAS",
		"Karhu O, Kansi P, Kuorinka I. Correcting working postures in industry: a practical "
		"method for analysis. Applied Ergonomics 8(4):199-201, 1977; Karhu O, Harkonen R, "
		"Sorvali P, Vepsalainen P. Observing working postures in industry: examples of OWAS "
		"application. Applied Ergonomics 12(1):13-17, 1981.",
		"Codes from the OWAS training material (20 deg back threshold; an arm raised when its "
		"elbow is at or above the shoulder). The 252-cell classification is the majority "
		"reading of eight public implementations (no primary copy was reachable); two cells "
		"are contested (back 3, arms 3, legs 7; back 4, arms 1, legs 3): the majority is used.",
		4,
		{ { 1, "AC 1", "normal postures: no corrective measures needed" },
		  { 2, "AC 2", "slightly harmful: corrective measures in the near future" },
		  { 3, "AC 3", "distinctly harmful: corrective measures as soon as possible" },
		  { 4, "AC 4", "extremely harmful: corrective measures immediately" } },
	},
};

/* what none of the three methods' scores here model (the report's last section) */
static const char *const not_modelled[] = {
	"One instant: the posture as it stands now. The methods score the worst or most held "
	"posture of a task, or (OWAS) postures sampled over the work: which posture, and how long "
	"it is held, is the assessor's choice.",
	"What a posture does not show comes from the inputs above: muscle use (static, repeated), "
	"coupling, REBA's activity, shock, arm support.",
	"The load is the mass of the objects the hands hold (grab); pushing, pulling and other "
	"forces are not measured.",
	"The angles are the manikin's joint geometry (no soft tissue, no clothing). Thresholds a "
	"method leaves open (a shoulder \"raised\", a trunk \"twisted\") are in the table above "
	"with their sources. A value on the edge between two bands scores the worse band.",
	"OWAS: walking (legs 7) is not observable in one posture and never given; the per-part "
	"frequency categories over the work are not computed.",
	"RULA and REBA score one arm, the worse of the two; the other arm's score is not in this "
	"report.",
};

/* ---- pieces ------------------------------------------------------------- */

static void
tag_text(FILE *f, const char *tag, const char *text)
{
	fprintf(f, "<%s>", tag);
	html_text(f, text);
	fprintf(f, "</%s>", tag);
}

static void
td(FILE *f, const char *text)
{
	tag_text(f, "td", text ? text : "");
}

/* the CSS colour of an action level's tint colour */
static void
level_style(FILE *f, enum assess_method m, int level)
{
	const float *c = tint_rgba[assess_level_colour(m, level)];
	fprintf(f, " style=\"background:#%02x%02x%02x\"", (int)(c[0] * 255 + 0.5f),
		(int)(c[1] * 255 + 0.5f), (int)(c[2] * 255 + 0.5f));
}

static const char css[] =
	"@page{size:A4;margin:6mm 8mm}"
	"html{font:6.1pt/1.17 'DejaVu Sans',Arial,sans-serif;color:#000;background:#fff}"
	"body{margin:0 auto;max-width:194mm}"
	"h1{font-size:10.5pt;margin:0}h2{font-size:7.2pt;margin:1.2mm 0 .4mm;"
	"border-bottom:.3pt solid #777}h3{font-size:6.4pt;margin:.6mm 0 .2mm}"
	"p{margin:.2mm 0}table{border-collapse:collapse;width:100%}"
	"th,td{border:.3pt solid #aaa;padding:0 .6mm;text-align:left;vertical-align:top}"
	"th{background:#eee}td.n{text-align:right;white-space:nowrap}"
	".top{display:flex;gap:3mm}.top figure{margin:0;flex:0 0 37mm}"
	".top figure img{width:37mm;height:auto;border:.3pt solid #aaa}.top .about{flex:1}"
	".small,.small td,.small th{font-size:5.6pt}.tiny{font-size:5.1pt}.cols2{columns:2;column-gap:4mm}"
	".angles{columns:6;column-gap:2mm}.angles p,.cols2 p{margin:0}.meta{color:#333}"
	"ul{margin:.2mm 0;padding-left:3.5mm}"
	"table.parts td:nth-child(1){width:8%}table.parts td:nth-child(2){width:15%}"
	"table.parts td:nth-child(3){width:22%}table.parts td:nth-child(4){width:47%}";

/* a number as the report prints it: -0.0 as 0.0 */
static double
clean(double v, double step)
{
	return fabs(v) < step / 2 ? 0 : v;
}

/* ---- sections ------------------------------------------------------------- */

static void
write_head(FILE *f, const struct assess_report *r)
{
	fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">", f);
	fputs("<title>", f);
	html_textf(f, "Posture assessment: %s", r->figure);
	fprintf(f, "</title><style>%s</style></head>\n<body>\n", css);
	fputs("<h1>", f);
	html_textf(f, "Posture assessment: %s", r->figure);
	fputs("</h1>\n<p class=\"meta\" id=\"made\">", f);
	html_textf(f, "Made %s by postured: RULA, REBA and OWAS of the posture as it stands.",
		   r->date);
	fputs("</p>\n", f);
}

/* the figure's size: list figures' words for it, in pairs of heading and value */
static void
write_about(FILE *f, const struct assess_report *r)
{
	static const struct {
		const char *key, *unit, *fmt;
	} rows[] = { { "sex", "", "" },           { "stature", "m", "%.3f" },
		     { "mass", "kg", "%.1f" },    { "population", "", "" },
		     { "percentile", "", "%.1f" }, { "mahalanobis", "", "%.3f" },
		     { "inside", "%", "%.1f" },   { "family", "", "" },
		     { "member", "", "%.0f" },    { "coverage", "%", "%.1f" } };
	const json_t *a = r->about;
	fputs("<div class=\"about\"><h2>Figure</h2><table id=\"figure\"><tr><th>name</th>", f);
	td(f, r->figure);
	int cell = 1; /* pairs so far in this row: four a row */
	for (size_t i = 0; a && i < sizeof rows / sizeof rows[0]; i++) {
		const json_t *v = json_object_get(a, rows[i].key);
		if (!v)
			continue;
		if (cell++ % 4 == 0)
			fputs("</tr><tr>", f);
		tag_text(f, "th", rows[i].key);
		fputs("<td>", f);
		if (json_is_string(v))
			html_text(f, json_string_value(v));
		else if (json_is_number(v))
			html_textf(f, rows[i].fmt, json_number_value(v));
		html_textf(f, rows[i].unit[0] ? " %s" : "%s", rows[i].unit);
		fputs("</td>", f);
	}
	fputs("</tr></table>", f);
	const json_t *given = a ? json_object_get(a, "given") : NULL;
	const json_t *ms = a ? json_object_get(a, "measures") : NULL;
	if (json_is_object(ms) && json_object_size(ms)) {
		fputs("<p id=\"measures\" class=\"small\"><b>measures</b> (mm, weightkg kg): ", f);
		const char *k;
		const json_t *v;
		int first = 1;
		json_object_foreach((json_t *)ms, k, v) {
			int was_given = 0;
			size_t gi;
			const json_t *g;
			json_array_foreach(given, gi, g) {
				if (json_is_string(g) && !strcmp(json_string_value(g), k))
					was_given = 1;
			}
			html_textf(f, "%s%s %.1f%s", first ? "" : "; ", k, json_number_value(v),
				   was_given ? " (given)" : "");
			first = 0;
		}
		fputs("</p>", f);
	}
}

static void
write_summary(FILE *f, const struct assess_report *r)
{
	fputs("<h2>Scores</h2><table id=\"summary\"><tr><th>method</th><th>score</th>"
	      "<th>action level</th><th>meaning</th><th>worst part</th></tr>",
	      f);
	for (int m = 0; m < ASSESS_NMETHODS; m++) {
		const struct assess_result *res = r->res[m];
		fprintf(f, "<tr data-method=\"%s\">", assess_json_method((enum assess_method)m));
		td(f, methods[m].title);
		fprintf(f, "<td class=\"n\">%d</td><td class=\"n\"", res->score);
		level_style(f, (enum assess_method)m, res->action_level);
		fprintf(f, ">%s %d</td>", m == ASSESS_OWAS ? "AC" : "AL", res->action_level);
		td(f, res->action);
		td(f, res->worst >= 0 && res->worst < res->nparts ? res->part[res->worst].name : "");
		fputs("</tr>", f);
	}
	fputs("</table>\n", f);
}

static void
write_part(FILE *f, const struct assess_result *res, int i)
{
	const struct assess_part *p = &res->part[i];
	fprintf(f, "<tr data-part=\"");
	html_text(f, p->name ? p->name : "");
	fputs("\">", f);
	td(f, p->name);
	fputs("<td>", f);
	if (p->angle_name && isfinite(p->angle))
		html_textf(f, "%s %.1f", p->angle_name, clean(p->angle, 0.1));
	fputs("</td>", f);
	fputs("<td>", f);
	html_textf(f, "%d: %s", p->base, p->band);
	fputs("</td><td>", f);
	for (int k = 0; k < p->nadj && k < ASSESS_MAX_ADJ; k++) {
		if (k)
			fputs("<br>", f);
		html_textf(f, "%+d %s", p->adj[k].value, p->adj[k].reason);
	}
	fprintf(f, "</td><td class=\"n\">%d / %d</td>", p->score, p->max);
	int lv = p->body ? assess_part_level(res, i) : -1;
	if (lv < 0) {
		fputs("<td></td>", f);
	} else {
		fputs("<td class=\"n\"", f);
		level_style(f, res->method, lv);
		fprintf(f, ">%d</td>", lv);
	}
	fputs("</tr>", f);
}

static void
write_method(FILE *f, const struct assess_report *r, enum assess_method m)
{
	const struct assess_result *res = r->res[m];
	const char *name = assess_json_method(m);
	fprintf(f, "<section class=\"method\" id=\"%s\" data-score=\"%d\" data-action-level=\"%d\">",
		name, res->score, res->action_level);
	fputs("<h2>", f);
	html_textf(f, "%s: score %d, %s %d", methods[m].title, res->score,
		   m == ASSESS_OWAS ? "action category" : "action level", res->action_level);
	if (res->side == ASSESS_SIDE_LEFT || res->side == ASSESS_SIDE_RIGHT)
		html_textf(f, " (%s arm)", res->side == ASSESS_SIDE_LEFT ? "left" : "right");
	if (res->code[0])
		html_textf(f, " (code %s)", res->code);
	fputs("</h2><p>", f);
	html_text(f, res->action ? res->action : "");
	fputs(" <span class=\"small\">(", f);
	for (int i = 0; i < methods[m].nlevels; i++)
		html_textf(f, "%s%s %s: %s", i ? "; " : "levels: ", m == ASSESS_OWAS ? "" : "score",
			   methods[m].levels[i].scores, methods[m].levels[i].words);
	fputs(")</span></p>", f);
	fputs("<table class=\"parts small\"><tr><th>part</th><th>angle (deg)</th><th>band</th>"
	      "<th>adjustments</th><th>score</th><th title=\"the level with this part alone as "
	      "measured, the rest at their lowest: the tint's colour\">alone</th></tr>",
	      f);
	for (int i = 0; i < res->nparts && i < ASSESS_MAX_PARTS; i++)
		write_part(f, res, i);
	/* the look-ups in one row: each table, its indices, the cell read */
	fputs("</table><table class=\"lookups small\"><tr><th>look-ups</th>", f);
	for (int i = 0; i < res->nlookups && i < ASSESS_MAX_LOOKUPS; i++) {
		const struct assess_lookup *l = &res->lookup[i];
		fputs("<td data-table=\"", f);
		html_text(f, l->table ? l->table : "?");
		fprintf(f, "\" data-value=\"%d\">", l->value);
		html_textf(f, "%s (", l->table ? l->table : "?");
		for (int k = 0; k < l->nidx && k < ASSESS_MAX_IDX; k++)
			html_textf(f, "%s%s %d", k ? ", " : "", l->idx_name[k] ? l->idx_name[k] : "?",
				   l->idx[k]);
		fprintf(f, ") = %d</td>", l->value);
	}
	fputs("</tr></table></section>\n", f);
}

/* what the scores were made with that the posture does not show */
static void
write_inputs(FILE *f, const struct assess_report *r)
{
	fputs("<h2>Inputs the posture does not show</h2><div id=\"inputs\" class=\"cols2 small\">",
	      f);
	for (int i = 0; i < r->ninputs; i++) {
		fputs("<p data-key=\"", f);
		html_text(f, r->input[i].key);
		fputs("\"><b>", f);
		html_text(f, r->input[i].key);
		fputs("</b> <span class=\"value\">", f);
		html_text(f, r->input[i].value);
		fputs("</span>: ", f);
		html_text(f, r->input[i].note);
		fputs("</p>", f);
	}
	fputs("</div>\n", f);
}

/* the thresholds the methods leave open: each value with its source */
static void
write_thresholds(FILE *f, const struct assess_report *r)
{
	fputs("<section><h2>Thresholds the methods leave open (set assess)</h2>"
	      "<div id=\"thresholds\" class=\"cols2 tiny\">",
	      f);
	for (size_t i = 0; i < assess_config_nkeys; i++) {
		const struct assess_config_key *k = &assess_config_keys[i];
		double v = *(const double *)((const char *)&r->cfg + k->offset);
		fprintf(f, "<p data-key=\"");
		html_text(f, k->key);
		fputs("\"><b>", f);
		html_text(f, k->key);
		fputs("</b> <span class=\"value\">", f);
		html_textf(f, "%g %s", v, k->unit);
		fputs("</span>: <span class=\"source\">", f);
		html_text(f, k->source);
		fputs("</span></p>", f);
	}
	fputs("</div></section>\n", f);
}

static void
write_angles(FILE *f, const struct assess_report *r)
{
	fputs("<section><h2>Body angles measured</h2><div class=\"angles tiny\" id=\"angles\">", f);
	for (size_t i = 0; i < body_angle_count; i++) {
		double v = body_angle_value(r->angles, i);
		fputs("<p>", f);
		if (!isfinite(v))
			html_textf(f, "%s: none", body_angle_names[i].name);
		else if (!strcmp(body_angle_names[i].unit, "flag"))
			html_textf(f, "%s: %s", body_angle_names[i].name, v != 0 ? "yes" : "no");
		else if (!strcmp(body_angle_names[i].unit, "count"))
			html_textf(f, "%s: %.0f", body_angle_names[i].name, v);
		else if (!strcmp(body_angle_names[i].unit, "deg"))
			html_textf(f, "%s: %.1f\u00b0", body_angle_names[i].name, clean(v, 0.1));
		else
			html_textf(f, "%s: %.3f %s", body_angle_names[i].name, clean(v, 0.001),
				   body_angle_names[i].unit);
		fputs("</p>", f);
	}
	fputs("</div></section>\n", f);
}

static void
write_sources(FILE *f)
{
	fputs("<section id=\"sources\"><h2>Sources</h2><ul class=\"tiny cols2\">", f);
	for (int m = 0; m < ASSESS_NMETHODS; m++) {
		fputs("<li>", f);
		html_textf(f, "%s: %s %s", methods[m].title, methods[m].cite, methods[m].tables);
		fputs("</li>", f);
	}
	fputs("<li>", f);
	html_text(f, "The \"alone\" column: the action level the score would have with that part "
		     "alone as measured and every other part (add-ons too) at its lowest score, "
		     "looked up in the method's tables; it is the colour a tinted view draws the "
		     "part in (green, yellow, orange, red: no action, action later, soon, now).");
	fputs("</li></ul></section>\n<section id=\"not-modelled\"><h2>Not modelled</h2>"
	      "<ul class=\"tiny cols2\">",
	      f);
	for (size_t i = 0; i < sizeof not_modelled / sizeof not_modelled[0]; i++)
		tag_text(f, "li", not_modelled[i]);
	fputs("</ul></section>\n", f);
}

int
assess_report_write(const struct assess_report *r, const char *path, char *err, size_t errlen)
{
	for (int m = 0; m < ASSESS_NMETHODS; m++)
		if (!r->res[m]) {
			snprintf(err, errlen, "no %s result", assess_json_method((enum assess_method)m));
			return -1;
		}
	struct export_file x;
	FILE *f = export_file_open(&x, path, err, errlen);
	if (!f)
		return -1;
	write_head(f, r);
	fputs("<div class=\"top\"><figure>", f);
	fprintf(f, "<img id=\"picture\" alt=\"the figure\" width=\"%d\" height=\"%d\" "
		   "src=\"data:image/png;base64,",
		r->png_w, r->png_h);
	html_base64(f, r->png, r->png_len);
	fputs("\"></figure>", f);
	write_about(f, r);
	write_summary(f, r);
	write_inputs(f, r);
	fputs("</div></div>\n", f);
	write_method(f, r, ASSESS_RULA);
	write_method(f, r, ASSESS_REBA);
	write_method(f, r, ASSESS_OWAS);
	write_angles(f, r);
	write_thresholds(f, r);
	write_sources(f);
	fputs("</body></html>\n", f);
	return export_file_commit(&x, err, errlen);
}

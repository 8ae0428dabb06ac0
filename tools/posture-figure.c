/*
 * posture-figure - inspect a figure: its dofs and limits, the global frames
 * of its sites for given postures, its centre of mass, the forces and
 * moments its joints carry under loads; export it as URDF, glTF or in the
 * figure language.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figure/figure.h"
#include "figure/human.h"
#include "figure/kin.h"
#include "figure/model.h"
#include "figure/population.h"
#include "figure/state.h"
#include "export/bvh.h"
#include "export/gltf.h"
#include "export/seg_mesh.h"
#include "export/urdf.h"
#include "assess/statics.h"
#include "pose/anthropometry.h"
#include "pose/load.h"

static const char usage[] =
	"usage: posture-figure [FIGURE OPTIONS] [POSTURE OPTIONS] COMMAND\n"
	"\n"
	"figure (default: the built-in human, male, 1.75 m, 75 kg):\n"
	"  --human               the built-in standard human figure\n"
	"  --sex male|female     its sex (sets the default stature and mass)\n"
	"  --stature METRES      its stature\n"
	"  --mass KG             its body mass\n"
	"  --measure NAME=VALUE  an ANSUR II measure the human must meet (mm; weightkg\n"
	"                        in kg), e.g. sittingheight=918; repeatable\n"
	"  --figure FILE         a figure file in the peabody language instead\n"
	"posture (default: the figure's initial posture):\n"
	"  --q-file FILE         postures, one a line: every dof value in order\n"
	"                        (radians, metres); '-' reads standard input\n"
	"  --random SEED         one random posture within the joint limits\n"
	"  --root SEG.SITE       re-root through this site (in the initial posture);\n"
	"                        postures then keep it fixed in space\n"
	"loads (the loads command):\n"
	"  --load SEG.SITE,FX,FY,FZ[,TX,TY,TZ]\n"
	"                        a force (N) and torque (N m), world frame (y up), at a\n"
	"                        site; repeatable\n"
	"  --weight SEG.SITE,KG  a weight hanging at a site (its force KG x 9.80665 N\n"
	"                        down); repeatable\n"
	"  --seated              the figure sits: the seat bears it under the ischial\n"
	"                        tuberosities, with the feet on the floor\n"
	"output:\n"
	"  --out FILE.urdf       urdf: write FILE.urdf and each segment's mesh beside it\n"
	"                        (FILE_SEGMENT.stl) instead of the URDF alone to stdout\n"
	"  --out FILE.glb        gltf: the file to write (required)\n"
	"  --out FILE.bvh        bvh: the file to write (required)\n"
	"commands:\n"
	"  summary   counts, mass, height, centre of mass, root\n"
	"  dofs      every dof: index, joint, kind and axis, limits, initial value\n"
	"  joints    every joint: its sites on the parent and the child side of the\n"
	"            current root's tree, and its number of dofs\n"
	"  sites     per posture, every site: position and rotation matrix (row-major)\n"
	"  com       per posture, the centre of mass\n"
	"  segments  per posture, every segment: its mass, the position of its centre\n"
	"            of mass, its frame's position and rotation matrix (row-major)\n"
	"  bounds    per posture, the bounding box of the posed meshes: min x y z, max x y z\n"
	"  urdf      the figure as URDF (hierarchy of the current root; geometry with --out)\n"
	"  gltf      the figure as binary glTF 2.0 with its meshes, posed as the initial\n"
	"            (or --random) posture; with --q-file its postures become an\n"
	"            animation, a keyframe every 0.5 s\n"
	"  bvh       the figure's skeleton and the --q-file's postures as BVH motion\n"
	"            frames, 0.5 s apart (without --q-file, the posture alone)\n"
	"  write     the figure in the figure language\n"
	"  measures  the human measured as ANSUR II measured people: NAME VALUE lines\n"
	"            (mm; weightkg in kg)\n"
	"  loads     per posture, one JSON line: the static equilibrium under gravity\n"
	"            and the --load and --weight loads: the supports' forces, every\n"
	"            joint's force and moment (proximal onto distal, world frame, N\n"
	"            and N m), its dofs' generalised torques and, for the human's\n"
	"            wrists, elbows, shoulders, L5/S1, hips, knees and ankles, the\n"
	"            moment about the anatomical axes\n";

/* a --load or --weight as given, read once the figure is built */
struct load_arg {
	const char *text;
	int weight;
};

struct options {
	int human;
	struct human_def hdef;
	const char *figure, *qfile, *root, *command, *out;
	long seed;
	int have_seed;
	int seated, nload;
	struct load_arg load[STATICS_MAX_LOADS];
};

static int
parse_double(const char *s, double *dest)
{
	char *end;
	errno = 0;
	*dest = strtod(s, &end);
	return s[0] && !*end && !errno && isfinite(*dest) ? 0 : -1;
}

/*
 * The measures not given, as the daemon's `load human NAME=MM ...` has them:
 * the built-in population's conditional expectation given the others (its
 * stature and mass included), so a manikin is the same whichever builds it.
 */
static int
complete_measures(struct human_def *hd, int stature_set, int mass_set)
{
	int cols[HUMAN_MEASURE_N], k = 0;
	double vals[HUMAN_MEASURE_N], all[POPULATION_NCOL];
	char err[256];
	if (stature_set) {
		hd->measure[HUMAN_M_STATURE] = hd->stature * 1000;
		hd->measure_given |= 1u << HUMAN_M_STATURE;
	}
	if (mass_set) {
		hd->measure[HUMAN_M_WEIGHTKG] = hd->mass;
		hd->measure_given |= 1u << HUMAN_M_WEIGHTKG;
	}
	for (int j = 0; j < HUMAN_MEASURE_N; j++)
		if (hd->measure_given >> j & 1u) {
			cols[k] = population_column(anthro_name((enum human_measure)j));
			vals[k++] = hd->measure[j];
		}
	if (population_predict(population_ansur2(), hd->sex, cols, vals, k, all, NULL, err,
			       sizeof err) < 0) {
		fprintf(stderr, "posture-figure: %s\n", err);
		return -1;
	}
	population_to_human(all, hd);
	return 0;
}

static int
parse_options(int argc, char **argv, struct options *o)
{
	o->human = 1;
	o->hdef = human_default_def(HUMAN_MALE);
	int stature_set = 0, mass_set = 0;
	double stature = 0, mass = 0, measure[HUMAN_MEASURE_N];
	unsigned given = 0;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
		int takes = strcmp(a, "--human") && strcmp(a, "--seated") && strncmp(a, "--help", 6) &&
			    a[0] == '-' && a[1];
		if (takes && !v) {
			fprintf(stderr, "posture-figure: %s needs a value\n", a);
			return -1;
		}
		if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
			fputs(usage, stdout);
			exit(0);
		} else if (!strcmp(a, "--human")) {
			o->human = 1;
		} else if (!strcmp(a, "--sex")) {
			if (strcmp(v, "male") && strcmp(v, "female")) {
				fprintf(stderr, "posture-figure: --sex is male or female\n");
				return -1;
			}
			o->hdef = human_default_def(!strcmp(v, "male") ? HUMAN_MALE : HUMAN_FEMALE);
			i++;
		} else if (!strcmp(a, "--stature")) {
			if (parse_double(v, &stature) < 0)
				goto bad_number;
			stature_set = 1;
			i++;
		} else if (!strcmp(a, "--mass")) {
			if (parse_double(v, &mass) < 0)
				goto bad_number;
			mass_set = 1;
			i++;
		} else if (!strcmp(a, "--measure")) {
			const char *eq = strchr(v, '=');
			char name[64];
			int k = -1;
			if (eq && (size_t)(eq - v) < sizeof name) {
				memcpy(name, v, (size_t)(eq - v));
				name[eq - v] = 0;
				k = anthro_find(name);
			}
			if (k < 0) {
				fprintf(stderr, "posture-figure: --measure takes NAME=VALUE with NAME one of");
				for (int j = 0; j < HUMAN_MEASURE_N; j++)
					fprintf(stderr, " %s", anthro_name((enum human_measure)j));
				fprintf(stderr, " (got '%s')\n", v);
				return -1;
			}
			if (parse_double(eq + 1, &measure[k]) < 0)
				goto bad_number;
			given |= 1u << k;
			i++;
		} else if (!strcmp(a, "--figure")) {
			o->figure = v;
			o->human = 0;
			i++;
		} else if (!strcmp(a, "--q-file")) {
			o->qfile = v;
			i++;
		} else if (!strcmp(a, "--random")) {
			char *end;
			o->seed = strtol(v, &end, 10);
			if (!v[0] || *end)
				goto bad_number;
			o->have_seed = 1;
			i++;
		} else if (!strcmp(a, "--root")) {
			o->root = v;
			i++;
		} else if (!strcmp(a, "--out")) {
			o->out = v;
			i++;
		} else if (!strcmp(a, "--load") || !strcmp(a, "--weight")) {
			if (o->nload == STATICS_MAX_LOADS) {
				fprintf(stderr, "posture-figure: more than %d loads\n", STATICS_MAX_LOADS);
				return -1;
			}
			o->load[o->nload].text = v;
			o->load[o->nload++].weight = a[2] == 'w';
			i++;
		} else if (!strcmp(a, "--seated")) {
			o->seated = 1;
		} else if (a[0] == '-') {
			fprintf(stderr, "posture-figure: unknown option %s\n%s", a, usage);
			return -1;
		} else if (!o->command) {
			o->command = a;
		} else {
			fprintf(stderr, "posture-figure: one command only (got %s and %s)\n",
				o->command, a);
			return -1;
		}
		continue;
	bad_number:
		fprintf(stderr, "posture-figure: %s takes a number, not '%s'\n", a, v);
		return -1;
	}
	if (stature_set)
		o->hdef.stature = stature;
	if (mass_set)
		o->hdef.mass = mass;
	/* a measured stature or weight is the figure's too */
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		if (given >> k & 1u)
			o->hdef.measure[k] = measure[k];
	o->hdef.measure_given = given;
	if ((given >> HUMAN_M_STATURE & 1u) && !stature_set)
		o->hdef.stature = measure[HUMAN_M_STATURE] / 1000;
	if ((given >> HUMAN_M_WEIGHTKG & 1u) && !mass_set)
		o->hdef.mass = measure[HUMAN_M_WEIGHTKG];
	if (given && !o->human) {
		fprintf(stderr, "posture-figure: --measure is for the built-in human, not --figure\n");
		return -1;
	}
	if (given && complete_measures(&o->hdef, stature_set, mass_set) < 0)
		return -1;
	if (!o->command) {
		fprintf(stderr, "posture-figure: no command\n%s", usage);
		return -1;
	}
	return 0;
}

static const char *
dof_type(const struct model *m, int d, char *buf, size_t len)
{
	snprintf(buf, len, "%c(%s%c)", m->dof_kind[d] == DOF_ROTATION ? 'R' : 'T',
		 m->dof_sign[d] < 0 ? "-" : "", "xyz"[m->dof_axis[d]]);
	return buf;
}

static void
print_summary(const struct model *m, const struct state *s)
{
	double lo = 1e300, hi = -1e300;
	for (int k = 0; k < m->nsite; k++) {
		lo = fmin(lo, s->site_xf[k].p[1]);
		hi = fmax(hi, s->site_xf[k].p[1]);
	}
	char root[2 * MODEL_NAME_MAX];
	printf("figure %s\n", m->name);
	printf("  segments %d, sites %d, joints %d, dofs %d, geoms %d, meshes %d\n", m->nseg,
	       m->nsite, m->njnt, m->ndof, m->ngeom, m->nmesh);
	printf("  mass %.3f kg\n", m->total_mass);
	printf("  sites span y %.4f .. %.4f m\n", lo, hi);
	printf("  centre of mass %.4f %.4f %.4f m\n", s->com[0], s->com[1], s->com[2]);
	printf("  root %s\n", model_site_fullname(m, s->root_site, root, sizeof root));
}

static void
print_dofs(const struct model *m)
{
	char t[16];
	printf("# index joint k type lower upper initial (radians or metres)\n");
	for (int d = 0; d < m->ndof; d++) {
		int j = m->dof_jnt[d];
		printf("%d %s %d %s %.17g %.17g %.17g\n", d, m->jnt_name[j], d - m->jnt_dof0[j],
		       dof_type(m, d, t, sizeof t), m->dof_lo[d], m->dof_hi[d], m->dof_init[d]);
	}
}

static void
print_joints(const struct model *m, const struct state *s)
{
	char from[2 * MODEL_NAME_MAX], to[2 * MODEL_NAME_MAX];
	printf("# joint parent-side-site child-side-site dofs\n");
	for (int j = 0; j < m->njnt; j++) {
		int fwd = s->jnt_dir[j] > 0;
		model_site_fullname(m, fwd ? m->jnt_site_from[j] : m->jnt_site_to[j], from, sizeof from);
		model_site_fullname(m, fwd ? m->jnt_site_to[j] : m->jnt_site_from[j], to, sizeof to);
		printf("%s %s %s %d\n", m->jnt_name[j], from, to, m->jnt_ndof[j]);
	}
}

static void
print_sites(const struct model *m, const struct state *s, int posture)
{
	char name[2 * MODEL_NAME_MAX];
	printf("posture %d\n", posture);
	for (int k = 0; k < m->nsite; k++) {
		const struct xform *x = &s->site_xf[k];
		printf("%s", model_site_fullname(m, k, name, sizeof name));
		for (int r = 0; r < 3; r++)
			printf(" %.17g", x->p[r]);
		for (int r = 0; r < 9; r++)
			printf(" %.17g", x->r[r]);
		printf("\n");
	}
}

static void
print_segments(const struct model *m, const struct state *s, int posture)
{
	printf("posture %d\n", posture);
	for (int seg = 0; seg < m->nseg; seg++) {
		const struct xform *x = &s->seg_xf[seg];
		double c[3];
		xform_apply(x, &m->seg_com[3 * seg], c);
		printf("%s %.17g %.17g %.17g %.17g", m->seg_name[seg], m->seg_mass[seg], c[0], c[1],
		       c[2]);
		for (int r = 0; r < 3; r++)
			printf(" %.17g", x->p[r]);
		for (int r = 0; r < 9; r++)
			printf(" %.17g", x->r[r]);
		printf("\n");
	}
}

/* every segment's mesh placed by the posture: one bounding box, as a viewer sees the figure */
static int
print_bounds(const struct model *m, const struct state *s, int posture)
{
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (int seg = 0; seg < m->nseg; seg++) {
		struct seg_mesh mesh;
		if (seg_mesh_build(m, seg, &mesh) < 0) {
			fprintf(stderr, "posture-figure: out of memory\n");
			return 1;
		}
		for (int v = 0; v < mesh.nvert; v++) {
			double local[3] = { mesh.pos[3 * v], mesh.pos[3 * v + 1], mesh.pos[3 * v + 2] };
			double w[3];
			xform_apply(&s->seg_xf[seg], local, w);
			for (int i = 0; i < 3; i++) {
				lo[i] = fmin(lo[i], w[i]);
				hi[i] = fmax(hi[i], w[i]);
			}
		}
		seg_mesh_free(&mesh);
	}
	printf("bounds %d %.17g %.17g %.17g %.17g %.17g %.17g\n", posture, lo[0], lo[1], lo[2],
	       hi[0], hi[1], hi[2]);
	return 0;
}

/* the URDF to stdout, or with its meshes to files */
static int
write_urdf(const struct model *m, const struct state *s, const char *out)
{
	if (!out)
		return urdf_write(m, s, NULL, stdout) < 0 ? 1 : 0;
	char err[512];
	int n = urdf_export(m, s, out, err, sizeof err);
	if (n < 0) {
		fprintf(stderr, "posture-figure: %s\n", err);
		return 1;
	}
	fprintf(stderr, "posture-figure: %s and %d mesh files written\n", out, n - 1);
	return 0;
}

/* the figure measured in ANSUR II's postures, whatever the posture options; 0 or 1 (said) */
static int
print_measures(const struct model *m)
{
	double v[HUMAN_MEASURE_N];
	char err[256];
	if (anthro_measure(m, v, err, sizeof err) < 0) {
		fprintf(stderr, "posture-figure: %s\n", err);
		return 1;
	}
	for (int k = 0; k < HUMAN_MEASURE_N; k++)
		printf("%s %.17g\n", anthro_name((enum human_measure)k), v[k]);
	return 0;
}

/* the loads the loads command solves for, read from the options against the figure */
struct loads_in {
	struct ext_load load[STATICS_MAX_LOADS];
	int n, seated;
};

/*
 * "SEG.SITE,X,Y,..." -> the load's segment and point and the numbers after
 * the site (n of them, n in [min, max]; what says what they are); 0, or
 * -1 said on stderr
 */
static int
parse_site_numbers(const struct model *m, const char *opt, const char *text, const char *what,
		   struct ext_load *l, double *v, int min, int max, int *n)
{
	const char *comma = strchr(text, ',');
	char name[2 * MODEL_NAME_MAX];
	int site = -1;
	if (comma && (size_t)(comma - text) < sizeof name) {
		memcpy(name, text, (size_t)(comma - text));
		name[comma - text] = 0;
		site = model_find_site(m, name);
	}
	if (site < 0) {
		fprintf(stderr, "posture-figure: %s '%s': no such site (give SEGMENT.SITE,...)\n", opt,
			text);
		return -1;
	}
	l->seg = m->site_seg[site];
	memcpy(l->local, m->site_loc[site].p, sizeof l->local);
	*n = 0;
	for (const char *p = comma; p && *p == ','; (*n)++) {
		char *end;
		errno = 0;
		if (*n == max || (v[*n] = strtod(p + 1, &end), end == p + 1) || errno ||
		    !isfinite(v[*n]) || (*end && *end != ',')) {
			*n = -1;
			break;
		}
		p = end;
	}
	if (*n < min) {
		fprintf(stderr, "posture-figure: %s '%s': SEGMENT.SITE and then %s\n", opt, text, what);
		return -1;
	}
	return 0;
}

#define LOAD_NUMBERS "a force FX,FY,FZ (N) and optionally a torque TX,TY,TZ (N m)"

/* the --load and --weight options as loads on m; 0, or -1 said on stderr */
static int
loads_read(const struct model *m, const struct options *o, struct loads_in *dest)
{
	memset(dest, 0, sizeof *dest);
	dest->seated = o->seated;
	for (int i = 0; i < o->nload; i++) {
		struct ext_load *l = &dest->load[i];
		double v[6] = { 0 };
		int n;
		if (o->load[i].weight) {
			if (parse_site_numbers(m, "--weight", o->load[i].text, "the mass (kg)", l, v, 1, 1,
					       &n) < 0)
				return -1;
			if (!(v[0] > 0)) {
				fprintf(stderr, "posture-figure: --weight '%s': the mass is above 0 kg\n",
					o->load[i].text);
				return -1;
			}
			l->mass = v[0];
			l->force[1] = -v[0] * LOAD_GRAVITY;
		} else {
			if (parse_site_numbers(m, "--load", o->load[i].text, LOAD_NUMBERS, l, v, 3, 6,
					       &n) < 0)
				return -1;
			if (n != 3 && n != 6) {
				fprintf(stderr, "posture-figure: --load '%s': SEGMENT.SITE and then %s\n",
					o->load[i].text, LOAD_NUMBERS);
				return -1;
			}
			memcpy(l->force, v, sizeof l->force);
			memcpy(l->torque, v + 3, sizeof l->torque);
		}
		dest->n++;
	}
	return 0;
}

static void
json_vec(const double v[3])
{
	printf("[%.17g,%.17g,%.17g]", v[0], v[1], v[2]);
}

/* the statics of one posture as a JSON line; 0, or 1 said on stderr */
static int
print_loads(const struct model *m, const struct state *s, const struct loads_in *li, int posture)
{
	static const char *const kind[] = { [STATICS_FOOT] = "foot", [STATICS_SEAT] = "seat",
					    [STATICS_ROOT] = "root" };
	static struct statics_result r; /* 40 kB: not on the stack */
	char err[512], name[2 * MODEL_NAME_MAX];
	if (statics_solve(m, s, li->load, li->n, li->seated, &r, err, sizeof err) < 0) {
		fprintf(stderr, "posture-figure: %s\n", err);
		return 1;
	}
	printf("{\"posture\":%d,\"weight\":%.17g,\"load_mass\":%.17g,\"seated\":%d,"
	       "\"contacts\":%d,\"lifts\":%d,\"tips\":%d,\"margin\":%.17g,\"cop\":",
	       posture, r.weight_n, r.load_mass, r.seated, r.contacts, r.lifts, r.tips, r.margin);
	json_vec(r.cop);
	printf(",\"supports\":[");
	for (int k = 0; k < r.nsupport; k++) {
		const struct statics_support *u = &r.support[k];
		printf("%s{\"site\":\"%s\",\"kind\":\"%s\",\"segment\":\"%s\",\"share\":%.17g,"
		       "\"point\":", k ? "," : "", model_site_fullname(m, u->site, name, sizeof name),
		       kind[u->kind], m->seg_name[u->seg], u->share);
		json_vec(u->point);
		printf(",\"force\":");
		json_vec(u->force);
		printf(",\"moment\":");
		json_vec(u->moment);
		printf("}");
	}
	printf("],\"joints\":{");
	for (int j = 0; j < r.njoint; j++) {
		printf("%s\"%s\":{\"distal\":\"%s\",\"point\":", j ? "," : "", m->jnt_name[j],
		       m->seg_name[r.distal_seg[j]]);
		json_vec(r.point[j]);
		printf(",\"force\":");
		json_vec(r.force[j]);
		printf(",\"moment\":");
		json_vec(r.moment[j]);
		printf(",\"dofs\":[");
		for (int d = m->jnt_dof0[j]; d < m->jnt_dof0[j] + m->jnt_ndof[j]; d++)
			printf("%s%.17g", d > m->jnt_dof0[j] ? "," : "", r.dof_torque[d]);
		printf("],\"anatomical\":");
		const char *const *axis = statics_axis_names(m, j);
		if (!axis)
			printf("null");
		for (int k = 0; axis && k < 3; k++)
			printf("%s\"%s\":%.17g%s", k ? "," : "{", axis[k], r.anat[j][k], k == 2 ? "}" : "");
		printf("}");
	}
	printf("}}\n");
	return 0;
}

/* the per-posture commands; returns 0, 1 on a failure (said), or -1 for an unknown command */
static int
per_posture(const struct model *m, const struct state *s, const char *cmd, int posture,
	    const char *out, const struct loads_in *li)
{
	if (!strcmp(cmd, "sites"))
		print_sites(m, s, posture);
	else if (!strcmp(cmd, "segments"))
		print_segments(m, s, posture);
	else if (!strcmp(cmd, "com"))
		printf("com %d %.17g %.17g %.17g mass %.17g\n", posture, s->com[0], s->com[1],
		       s->com[2], m->total_mass);
	else if (!strcmp(cmd, "summary"))
		print_summary(m, s);
	else if (!strcmp(cmd, "bounds"))
		return print_bounds(m, s, posture);
	else if (!strcmp(cmd, "urdf"))
		return write_urdf(m, s, out);
	else if (!strcmp(cmd, "write"))
		return figure_write(m, stdout) < 0 ? 1 : 0;
	else if (!strcmp(cmd, "dofs"))
		print_dofs(m);
	else if (!strcmp(cmd, "joints"))
		print_joints(m, s);
	else if (!strcmp(cmd, "loads"))
		return print_loads(m, s, li, posture);
	else
		return -1;
	return 0;
}

/* reads one line of ndof numbers; 1 read, 0 end of file, -1 error */
static int
read_posture(FILE *f, const struct model *m, double *q, int *lineno)
{
	char line[1 << 16];
	while (fgets(line, sizeof line, f)) {
		++*lineno;
		if (!strchr(line, '\n') && !feof(f)) {
			fprintf(stderr, "posture-figure: q-file line %d is too long\n", *lineno);
			return -1;
		}
		char *p = line, *end;
		while (*p == ' ' || *p == '\t')
			p++;
		if (*p == '\n' || *p == '#' || !*p)
			continue;
		for (int d = 0; d < m->ndof; d++) {
			errno = 0;
			q[d] = strtod(p, &end);
			if (end == p || errno || !isfinite(q[d])) {
				fprintf(stderr, "posture-figure: q-file line %d: value %d of %d is not a number\n",
					*lineno, d + 1, m->ndof);
				return -1;
			}
			p = end;
		}
		while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
			p++;
		if (*p) {
			fprintf(stderr, "posture-figure: q-file line %d: more than %d values\n",
				*lineno, m->ndof);
			return -1;
		}
		return 1;
	}
	return 0;
}

static int
set_root(const struct model *m, struct state *s, const char *root)
{
	if (!root)
		return 0;
	int site = model_find_site(m, root);
	if (site < 0) {
		fprintf(stderr, "posture-figure: no site '%s' (give SEGMENT.SITE)\n", root);
		return -1;
	}
	return kin_set_root(m, s, site);
}

/* the q-file, or standard input for '-'; NULL said on stderr */
static FILE *
qfile_open(const char *path)
{
	FILE *f = strcmp(path, "-") ? fopen(path, "r") : stdin;
	if (!f)
		fprintf(stderr, "posture-figure: %s: %s\n", path, strerror(errno));
	return f;
}

static void
qfile_close(FILE *f)
{
	if (f != stdin)
		fclose(f);
}

/* every posture of a q-file, each a state of its own: for commands that take them all at once */
struct postures {
	struct state **s;
	int n, cap;
};

static void
postures_free(struct postures *p)
{
	for (int k = 0; k < p->n; k++)
		state_free(p->s[k]);
	free(p->s);
	memset(p, 0, sizeof *p);
}

/*
 * Reads the q-file's postures, each rooted as s (the root chosen in the
 * initial posture stays fixed in space) with its global frames computed.
 * 0, or -1 said on stderr (dest then holds none).
 */
static int
postures_read(const struct model *m, const struct state *s, const char *qfile,
	      struct postures *dest)
{
	memset(dest, 0, sizeof *dest);
	FILE *f = qfile_open(qfile);
	if (!f)
		return -1;
	int lineno = 0, got;
	struct state *next = NULL;
	for (;;) {
		if (!next && !(next = state_make(m))) {
			fprintf(stderr, "posture-figure: out of memory\n");
			got = -1;
			break;
		}
		state_copy(m, s, next);
		if ((got = read_posture(f, m, next->q, &lineno)) <= 0)
			break;
		kin_update(m, next);
		if (dest->n == dest->cap) {
			int cap = dest->cap ? 2 * dest->cap : 64;
			struct state **grown = realloc(dest->s, sizeof *grown * (size_t)cap);
			if (!grown) {
				fprintf(stderr, "posture-figure: out of memory\n");
				got = -1;
				break;
			}
			dest->s = grown;
			dest->cap = cap;
		}
		dest->s[dest->n++] = next;
		next = NULL;
	}
	state_free(next);
	qfile_close(f);
	if (got < 0)
		postures_free(dest);
	return got < 0 ? -1 : 0;
}

/*
 * The commands that take every posture at once: gltf (the posture now in
 * its nodes, the q-file's postures as its animation) and bvh (the q-file's
 * postures as its frames; without one, the posture now alone).
 */
static int
write_motion(const struct model *m, const struct state *s, const char *cmd, const char *qfile,
	     const char *out)
{
	const char *ext = !strcmp(cmd, "gltf") ? "glb" : "bvh";
	if (!out) {
		fprintf(stderr, "posture-figure: %s needs --out FILE.%s\n", cmd, ext);
		return 2;
	}
	struct postures p = { 0 };
	if (qfile && postures_read(m, s, qfile, &p) < 0)
		return 1;
	if (qfile && !p.n) {
		fprintf(stderr, "posture-figure: %s holds no posture\n", qfile);
		return 1;
	}
	const struct state *only[1] = { s };
	struct motion mo = { .name = m->name, .m = m, .now = s,
			     .frames = (const struct state *const *)p.s, .nframes = p.n };
	char err[512];
	int rc;
	if (ext[0] == 'g') {
		rc = gltf_export(&mo, 1, MOTION_FRAME_SECONDS, out, err, sizeof err);
	} else {
		if (!p.n) {
			mo.frames = only;
			mo.nframes = 1;
		}
		rc = bvh_export(&mo, MOTION_FRAME_SECONDS, out, err, sizeof err);
	}
	if (rc < 0)
		fprintf(stderr, "posture-figure: %s\n", err);
	else
		fprintf(stderr, "posture-figure: %s written: %d segments, %d frames\n", out,
			m->nseg, mo.nframes);
	postures_free(&p);
	return rc < 0 ? 1 : 0;
}

int
main(int argc, char **argv)
{
	struct options o = { 0 };
	if (parse_options(argc, argv, &o) < 0)
		return 2;
	char err[512] = "";
	struct model *m = o.human ? human_build(&o.hdef, err, sizeof err)
				  : figure_read_file(o.figure, err, sizeof err);
	if (!m) {
		fprintf(stderr, "posture-figure: %s\n", err);
		return 1;
	}
	struct state *s = state_make(m);
	int rc = 0;
	if (!s) {
		fprintf(stderr, "posture-figure: out of memory\n");
		model_free(m);
		return 1;
	}
	kin_update(m, s);
	/* the root is chosen in the initial posture and stays fixed in space */
	static struct loads_in li;
	if (set_root(m, s, o.root) < 0 || loads_read(m, &o, &li) < 0) {
		rc = 1;
		goto out;
	}
	if (o.have_seed) {
		srand((unsigned)o.seed);
		for (int d = 0; d < m->ndof; d++)
			s->q[d] = m->dof_lo[d] + (m->dof_hi[d] - m->dof_lo[d]) * rand() / RAND_MAX;
		kin_update(m, s);
	}
	/* the commands that take every posture at once */
	if (!strcmp(o.command, "measures")) {
		rc = print_measures(m);
		goto out;
	}
	if (!strcmp(o.command, "gltf") || !strcmp(o.command, "bvh")) {
		rc = write_motion(m, s, o.command, o.qfile, o.out);
		goto out;
	}
	if (!o.qfile) {
		int got = per_posture(m, s, o.command, 0, o.out, &li);
		if (got < 0)
			fprintf(stderr, "posture-figure: unknown command '%s'\n%s", o.command, usage);
		rc = got < 0 ? 2 : got;
		goto out;
	}
	FILE *f = qfile_open(o.qfile);
	if (!f) {
		rc = 1;
		goto out;
	}
	int lineno = 0, n = 0, got;
	while ((got = read_posture(f, m, s->q, &lineno)) > 0) {
		kin_update(m, s);
		int done = per_posture(m, s, o.command, n++, o.out, &li);
		if (done) {
			if (done < 0)
				fprintf(stderr, "posture-figure: unknown command '%s'\n", o.command);
			rc = done < 0 ? 2 : done;
			break;
		}
	}
	if (got < 0)
		rc = 1;
	qfile_close(f);
out:
	if (fflush(stdout) != 0)
		rc = 1;
	state_free(s);
	model_free(m);
	return rc;
}

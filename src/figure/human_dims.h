/*
 * human_dims.h - where the human's joint centres go when ANSUR II measures
 * are given, and the landmark offsets the figure's sites take (human_dims.c
 * says how; human_data.c lays the figure out from them).
 */
#ifndef POSTURE_HUMAN_DIMS_H
#define POSTURE_HUMAN_DIMS_H

#include <stddef.h>

#include "figure/measures.h"

/*
 * Where the joint centres are, before the balance lean: the stature
 * fractions of today's figure, or what the given measures set (human_dims.c).
 * Heights are above the floor, lateral distances from the midline (left
 * side), metres.
 */
struct human_dims {
	int measured;                  /* 0: every value is today's stature fraction */
	double y_ankle, y_knee, y_hip; /* joint centre heights */
	double hx;                     /* hip joint centres from the midline */
	double y_asis;                 /* anterior superior iliac spines, before the trunk map */
	double lf, fw;                 /* foot length (heel to toe tip) and breadth */
	double hand_len;               /* de Leva's hand segment: wrist to third metacarpale */
	double gh_x, gh_y;             /* shoulder joint centre */
	double y_elbow, y_wrist, y_tip, y_eye;
	/*
	 * The trunk map: heights between today's hip height (trunk_from) and
	 * C7/T1 move linearly so that the hip is at y_hip and C7/T1 stays;
	 * identity for today's figure.
	 */
	double trunk_from;
	double acromion[3];               /* the acromion (layout frame) */
	double radiale_upper_y, radiale_y; /* the two radiale sites' heights */
	double v[HUMAN_MEASURE_N];        /* measured: the measures met (m; weightkg in kg) */
};

/*
 * ANSUR II means as fractions of stature (tools/ansur2_landmarks.py; the
 * relations are in its header), men and women.
 */
struct human_lm_fractions {
	double acromion_y;     /* acromion above the shoulder joint (ANSUR acromion-radiale
				  length less de Leva's shoulder-to-elbow) */
	double stylion_z;      /* stylion ahead of the wrist's axis (wrist circumference / 2 pi) */
	double acromion_x;     /* acromion outside the shoulder joint (from span) */
	double seat;           /* seat below the hip joint centres, sitting */
	double midpatella_y;   /* midpatella above the knee joint centre */
	double suprapatella;   /* suprapatella ahead of the knee axis (above it, seated) */
	double popliteal;      /* popliteal behind the knee axis (below it, seated) */
	double buttock;        /* buttock behind the hip joint centres */
	double shoulder_blade; /* shoulder blades behind the shoulder joints */
	double trochanterion_x; /* hip breadth / 2 */
	double tibiale_y;      /* tibiale above the knee joint centre */
	double iliocristale_y; /* iliocristale above the hip joint centre */
	double iliocristale_x; /* bicristal breadth / 2 */
	double malleolus_x;    /* bimalleolar breadth / 2 */
	double tragion_y;      /* tragion below the vertex */
	double tragion_x;      /* head breadth / 2 */
};

/* the ANSUR II offsets of the sex's landmarks */
const struct human_lm_fractions *human_lm_fractions(int female);

/*
 * Assumptions (no single published value; fractions of stature): the
 * radiale a little outside the elbow joint centre (about half the elbow's
 * breadth); the pinch point of thumbtip reach (thumb tip on the index
 * finger) 0.6 hand lengths below the wrist and a little ahead of it; the
 * lateral femoral epicondyle and the tibiale about half the knee's breadth
 * out and in; the suprapatella a little above the knee axis standing; the
 * ischial tuberosities, buttocks, shoulder blades and cervicale where the
 * body's outline puts them (only their depth or height enters a measure).
 */
#define HUMAN_LM_RADIALE_X 0.014
#define HUMAN_LM_PINCH 0.6
#define HUMAN_LM_THUMB_Z 0.01
#define HUMAN_LM_EPICONDYLE_X 0.028
#define HUMAN_LM_TIBIALE_X 0.025
#define HUMAN_LM_SUPRAPATELLA_Y 0.02

/* bounds of what the measures leave free, fractions of stature (every ANSUR II subject within) */
#define HUMAN_LM_SEAT_LO (-0.04)
#define HUMAN_LM_SEAT_HI 0.12
#define HUMAN_LM_KNEE_DEPTH_LO 0.005
#define HUMAN_LM_SUPRAPATELLA_HI 0.08
#define HUMAN_LM_POPLITEAL_HI 0.12
#define HUMAN_LM_BUTTOCK_LO 0.01
#define HUMAN_LM_BUTTOCK_HI 0.22
#define HUMAN_LM_BLADE_LO 0.01
#define HUMAN_LM_BLADE_HI 0.23
#define HUMAN_LM_OVERHANG_LO (-0.05)
#define HUMAN_LM_OVERHANG_HI 0.09
#define HUMAN_LM_RADIALE_GAP_LO (-0.05)
#define HUMAN_LM_RADIALE_GAP_HI 0.04

/* what a build from measures is given, and what today's figure would be */
struct human_dims_in {
	double H, mass; /* m, kg: the definition's stature and mass */
	int female;
	const double *measure; /* HUMAN_MEASURE_N values, mm (weightkg: kg) */
	unsigned given;        /* bit k: measure[k] is given */
	double c7;             /* C7/T1's height (one de Leva head length below the vertex) */
};

/*
 * D holds today's figure (the trunk map's origin and the hand's length in
 * proportion come from it); overrides what the measures set. 0, or -1 with
 * why in err.
 */
int human_dims_measured(const struct human_dims_in *in, struct human_dims *D, char *err,
			size_t errlen);

/* a height of today's trunk moved onto this figure's (C7/T1 at c7), and back */
double human_trunk_map(const struct human_dims *D, double c7, double y);
double human_trunk_unmap(const struct human_dims *D, double c7, double y);

/* the seat's depth below the hip joint centres: sittingheight's, or the ANSUR mean */
double human_seat_depth(const struct human_dims *D, double H, int female);

/* 0 when v (m) lies in [lo, hi] stature fractions, else -1 saying what and from which measures */
int human_dims_within(double v, double lo, double hi, double H, const char *what, const char *from,
		      char *err, size_t errlen);

#endif

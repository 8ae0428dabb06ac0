/*
 * measures.h - the ANSUR II measures a manikin is built from and measured by.
 *
 * Names are ANSUR II's column names (Gordon et al. 2014, NATICK/TR-15/007),
 * so users find them as they know them. Lengths are millimetres; weightkg is
 * kilograms (the survey's files hold tenths of a kilogram).
 */
#ifndef POSTURE_MEASURES_H
#define POSTURE_MEASURES_H

/* X(ENUM_SUFFIX, "ansur_name") in a fixed order */
#define HUMAN_MEASURES(X)                                     \
	X(STATURE, "stature")                                 \
	X(ACROMIALHEIGHT, "acromialheight")                   \
	X(WRISTHEIGHT, "wristheight")                         \
	X(TROCHANTERIONHEIGHT, "trochanterionheight")         \
	X(KNEEHEIGHTMIDPATELLA, "kneeheightmidpatella")       \
	X(LATERALMALLEOLUSHEIGHT, "lateralmalleolusheight")   \
	X(SITTINGHEIGHT, "sittingheight")                     \
	X(EYEHEIGHTSITTING, "eyeheightsitting")               \
	X(ACROMIONRADIALELENGTH, "acromionradialelength")     \
	X(RADIALESTYLIONLENGTH, "radialestylionlength")       \
	X(HANDLENGTH, "handlength")                           \
	X(FOOTLENGTH, "footlength")                           \
	X(BUTTOCKKNEELENGTH, "buttockkneelength")             \
	X(KNEEHEIGHTSITTING, "kneeheightsitting")             \
	X(POPLITEALHEIGHT, "poplitealheight")                 \
	X(BIACROMIALBREADTH, "biacromialbreadth")             \
	X(HIPBREADTH, "hipbreadth")                           \
	X(SPAN, "span")                                       \
	X(THUMBTIPREACH, "thumbtipreach")                     \
	X(WEIGHTKG, "weightkg")

#define HUMAN_MEASURE_ENUM(e, s) HUMAN_M_##e,
enum human_measure { HUMAN_MEASURES(HUMAN_MEASURE_ENUM) HUMAN_MEASURE_N };
#undef HUMAN_MEASURE_ENUM

#endif

/*
 * mathx.h - double-precision rigid transforms for kinematics.
 *
 * cglm is float-only; forward kinematics must agree with an independent
 * reference to 1e-9 m and IK gradients with finite differences to 1e-6
 * relative, which float cannot give. So kinematics runs in double here and
 * converts to cglm types only at the rendering boundary (mathx_to_mat4).
 *
 * Conventions: metres and radians, y up, right-handed. A transform maps
 * local to global: x_global = r * x_local + p. Rotation matrices are
 * row-major 3x3. Quaternions are (x, y, z, w), w last, as cglm's versor.
 */
#ifndef POSTURE_MATHX_H
#define POSTURE_MATHX_H

#include <math.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

struct xform {
	double r[9]; /* row-major rotation */
	double p[3]; /* translation */
};

static inline void
xform_identity(struct xform *dest)
{
	static const struct xform id = { { 1, 0, 0, 0, 1, 0, 0, 0, 1 }, { 0, 0, 0 } };
	*dest = id;
}

/* dest = a * b; dest may alias neither a nor b */
static inline void
xform_mul(const struct xform *a, const struct xform *b, struct xform *dest)
{
	const double *A = a->r, *B = b->r;
	double *D = dest->r;
	for (int i = 0; i < 3; i++) {
		D[3 * i + 0] = A[3 * i] * B[0] + A[3 * i + 1] * B[3] + A[3 * i + 2] * B[6];
		D[3 * i + 1] = A[3 * i] * B[1] + A[3 * i + 1] * B[4] + A[3 * i + 2] * B[7];
		D[3 * i + 2] = A[3 * i] * B[2] + A[3 * i + 1] * B[5] + A[3 * i + 2] * B[8];
		dest->p[i] = A[3 * i] * b->p[0] + A[3 * i + 1] * b->p[1] + A[3 * i + 2] * b->p[2] +
			     a->p[i];
	}
}

/* dest = a^-1 (rigid inverse: transpose and a dot product) */
static inline void
xform_inv(const struct xform *a, struct xform *dest)
{
	const double *A = a->r;
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			dest->r[3 * i + j] = A[3 * j + i];
	for (int i = 0; i < 3; i++)
		dest->p[i] = -(A[i] * a->p[0] + A[3 + i] * a->p[1] + A[6 + i] * a->p[2]);
}

/* dest = a * b^-1 without forming the inverse */
static inline void
xform_mul_inv(const struct xform *a, const struct xform *b, struct xform *dest)
{
	struct xform bi;
	xform_inv(b, &bi);
	xform_mul(a, &bi, dest);
}

/* transform a point */
/* 1 when every number of the transform is finite */
static inline int
xform_finite(const struct xform *x)
{
	for (int i = 0; i < 9; i++)
		if (!isfinite(x->r[i]))
			return 0;
	return isfinite(x->p[0]) && isfinite(x->p[1]) && isfinite(x->p[2]);
}

static inline void
xform_apply(const struct xform *a, const double v[3], double dest[3])
{
	double t[3];
	for (int i = 0; i < 3; i++)
		t[i] = a->r[3 * i] * v[0] + a->r[3 * i + 1] * v[1] + a->r[3 * i + 2] * v[2] + a->p[i];
	memcpy(dest, t, sizeof t);
}

/* rotate a vector */
static inline void
xform_rotate(const struct xform *a, const double v[3], double dest[3])
{
	double t[3];
	for (int i = 0; i < 3; i++)
		t[i] = a->r[3 * i] * v[0] + a->r[3 * i + 1] * v[1] + a->r[3 * i + 2] * v[2];
	memcpy(dest, t, sizeof t);
}

/* rotation matrix of a unit quaternion (x, y, z, w) */
static inline void
mathx_quat_to_mat(const double q[4], double dest[9])
{
	double x = q[0], y = q[1], z = q[2], w = q[3];
	dest[0] = 1 - 2 * (y * y + z * z);
	dest[1] = 2 * (x * y - z * w);
	dest[2] = 2 * (x * z + y * w);
	dest[3] = 2 * (x * y + z * w);
	dest[4] = 1 - 2 * (x * x + z * z);
	dest[5] = 2 * (y * z - x * w);
	dest[6] = 2 * (x * z - y * w);
	dest[7] = 2 * (y * z + x * w);
	dest[8] = 1 - 2 * (x * x + y * y);
}

/* unit quaternion (x, y, z, w, w >= 0) of a rotation matrix (Shepperd's method) */
static inline void
mathx_mat_to_quat(const double m[9], double dest[4])
{
	double tr = m[0] + m[4] + m[8], s;
	if (tr > 0) {
		s = sqrt(tr + 1.0) * 2;
		dest[3] = 0.25 * s;
		dest[0] = (m[7] - m[5]) / s;
		dest[1] = (m[2] - m[6]) / s;
		dest[2] = (m[3] - m[1]) / s;
	} else if (m[0] > m[4] && m[0] > m[8]) {
		s = sqrt(1.0 + m[0] - m[4] - m[8]) * 2;
		dest[3] = (m[7] - m[5]) / s;
		dest[0] = 0.25 * s;
		dest[1] = (m[1] + m[3]) / s;
		dest[2] = (m[2] + m[6]) / s;
	} else if (m[4] > m[8]) {
		s = sqrt(1.0 + m[4] - m[0] - m[8]) * 2;
		dest[3] = (m[2] - m[6]) / s;
		dest[0] = (m[1] + m[3]) / s;
		dest[1] = 0.25 * s;
		dest[2] = (m[5] + m[7]) / s;
	} else {
		s = sqrt(1.0 + m[8] - m[0] - m[4]) * 2;
		dest[3] = (m[3] - m[1]) / s;
		dest[0] = (m[2] + m[6]) / s;
		dest[1] = (m[5] + m[7]) / s;
		dest[2] = 0.25 * s;
	}
	if (dest[3] < 0)
		for (int i = 0; i < 4; i++)
			dest[i] = -dest[i];
}

/* dest = a * b (Hamilton product, w last) */
static inline void
mathx_quat_mul(const double a[4], const double b[4], double dest[4])
{
	double t[4];
	t[0] = a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1];
	t[1] = a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0];
	t[2] = a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3];
	t[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
	memcpy(dest, t, sizeof t);
}

/* quaternion of a rotation by angle about a unit axis */
static inline void
mathx_quat_axis_angle(const double axis[3], double angle, double dest[4])
{
	double s = sin(angle / 2);
	dest[0] = axis[0] * s;
	dest[1] = axis[1] * s;
	dest[2] = axis[2] * s;
	dest[3] = cos(angle / 2);
}

/* transform from a translation and a unit quaternion */
static inline void
xform_from_pos_quat(const double p[3], const double q[4], struct xform *dest)
{
	mathx_quat_to_mat(q, dest->r);
	memcpy(dest->p, p, sizeof dest->p);
}

/*
 * elementary joint transform: rotation about (sign * axis) by value, or
 * translation along it. axis is 0, 1, 2 for x, y, z; sign is +1 or -1.
 */
static inline void
xform_elementary(int is_translation, int axis, int sign, double value, struct xform *dest)
{
	xform_identity(dest);
	if (is_translation) {
		dest->p[axis] = sign * value;
		return;
	}
	double c = cos(value), s = sign * sin(value);
	int i = (axis + 1) % 3, j = (axis + 2) % 3;
	dest->r[3 * i + i] = c;
	dest->r[3 * i + j] = -s;
	dest->r[3 * j + i] = s;
	dest->r[3 * j + j] = c;
}

static inline void
mathx_cross(const double a[3], const double b[3], double dest[3])
{
	double t[3] = { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
			a[0] * b[1] - a[1] * b[0] };
	memcpy(dest, t, sizeof t);
}

static inline double
mathx_dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* dest = a b for 3x3 row-major matrices; dest may be a or b */
static inline void
mathx_mat3_mul(const double a[9], const double b[9], double dest[9])
{
	double t[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			t[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
	for (int i = 0; i < 9; i++)
		dest[i] = t[i];
}

/* dest = a^T b; dest may be a or b */
static inline void
mathx_mat3_tmul(const double a[9], const double b[9], double dest[9])
{
	double at[9];
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			at[3 * i + j] = a[3 * j + i];
	mathx_mat3_mul(at, b, dest);
}

/* rotation by angle (radians) about +y, the vertical: +z turns toward +x */
static inline void
mathx_rot_y(double angle, double dest[9])
{
	double c = cos(angle), s = sin(angle);
	const double r[9] = { c, 0, s, 0, 1, 0, -s, 0, c };
	for (int i = 0; i < 9; i++)
		dest[i] = r[i];
}

/*
 * The rotation vector of r (the log map): its axis times its angle, the
 * angle in 0..pi. Through the quaternion, which stays well conditioned at
 * every angle, where the matrix's antisymmetric part vanishes near pi.
 */
static inline void
mathx_rotation_vector(const double r[9], double dest[3])
{
	double q[4];
	mathx_mat_to_quat(r, q);
	double s = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
	/* 2 atan2(s, w) / s, and its limit 2 / w as s goes to 0 */
	double k = s > 1e-12 ? 2 * atan2(s, q[3]) / s : 2 / q[3];
	for (int i = 0; i < 3; i++)
		dest[i] = q[i] * k;
}

/* rotation angle (radians, 0..pi) between two rotation matrices */
static inline double
mathx_rot_angle_between(const double a[9], const double b[9])
{
	double tr = 0; /* trace of a^T b */
	for (int i = 0; i < 9; i++)
		tr += a[i] * b[i];
	double c = (tr - 1) / 2;
	if (c > 1)
		c = 1;
	if (c < -1)
		c = -1;
	return acos(c);
}

#endif

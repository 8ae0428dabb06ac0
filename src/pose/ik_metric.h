/*
 * ik_metric.h - the variable metric of the solver (§4.4): the inverse
 * Hessian estimate that BFGS refines, started from the inverse of the
 * Gauss-Newton metric over the variables that are free to move. Plain
 * row-major n x n arrays; nothing here knows constraints or figures.
 */
#ifndef POSTURE_IK_METRIC_H
#define POSTURE_IK_METRIC_H

/* dest (n x n) = scale times the identity */
void ik_metric_reset(int n, double scale, double *dest);

/*
 * BFGS update of the inverse Hessian dest (n x n) with the step s, the
 * gradient change y and sy = s.y > 0; hy is n doubles of scratch.
 */
void ik_metric_bfgs(int n, const double *s, const double *y, double sy, double *hy, double *dest);

/*
 * dest (n x n) = (B_FF + mu I)^-1 over the free variables F (pin[i] 0),
 * by Cholesky, with mu a millionth of B's largest free diagonal entry;
 * pinned variables get zero rows and columns. B is spent; L (n x n) and
 * free_idx (n) are scratch. Returns 0, or -1 when the free block is not
 * positive definite.
 */
int ik_metric_invert(int n, double *B, const unsigned char *pin, double *L, int *free_idx,
		     double *dest);

#endif

/* orccad_dynamics.c: the rigid-body dynamics computed torque needs — the mass matrix M(q)
 * (composite rigid body algorithm) and the nonlinear effects N(q, qdot) (recursive
 * Newton-Euler with zero acceleration) — of a chain of revolute joints, on the model that
 * orccad emits from the robot file through Pinocchio (joint placements, axes, inertias,
 * armature, gravity). Pinocchio's conventions: a motion is [v; w], a force [f; n], each
 * quantity in its joint's frame; M includes the armature on its diagonal. The operations are
 * Pinocchio's algorithms, not its floating-point order: the values agree with Pinocchio's
 * within a few ULP (tests/sil/test_kinds.py: 1e-12 relative). C99, no allocation, no
 * recursion. */
#include <math.h>
#include <string.h>

#include "orccad_dynamics.h"

typedef struct {
    double r[9]; /* rotation, row major: parent <- child */
    double p[3]; /* the child frame's origin in the parent frame */
} se3;

static void cross(const double *a, const double *b, double *out)
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
           z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static void rotate(const double *r, const double *a, double *out)
{
    int i;
    double t[3];
    for (i = 0; i < 3; i++) {
        t[i] = r[3 * i] * a[0] + r[3 * i + 1] * a[1] + r[3 * i + 2] * a[2];
    }
    memcpy(out, t, sizeof t);
}

static void rotate_t(const double *r, const double *a, double *out)
{
    int i;
    double t[3];
    for (i = 0; i < 3; i++) {
        t[i] = r[i] * a[0] + r[3 + i] * a[1] + r[6 + i] * a[2];
    }
    memcpy(out, t, sizeof t);
}

/* the joint's transform to its parent: placement * rotation(axis, q) */
static void joint_transform(const orc_joint *j, double q, se3 *out)
{
    double c = cos(q), s = sin(q), v = 1.0 - c, rot[9];
    const double *a = j->axis;
    int i, k;
    rot[0] = c + a[0] * a[0] * v;
    rot[1] = a[0] * a[1] * v - a[2] * s;
    rot[2] = a[0] * a[2] * v + a[1] * s;
    rot[3] = a[1] * a[0] * v + a[2] * s;
    rot[4] = c + a[1] * a[1] * v;
    rot[5] = a[1] * a[2] * v - a[0] * s;
    rot[6] = a[2] * a[0] * v - a[1] * s;
    rot[7] = a[2] * a[1] * v + a[0] * s;
    rot[8] = c + a[2] * a[2] * v;
    for (i = 0; i < 3; i++) {
        for (k = 0; k < 3; k++) {
            out->r[3 * i + k] = j->rotation[3 * i] * rot[k] + j->rotation[3 * i + 1] * rot[3 + k]
                                + j->rotation[3 * i + 2] * rot[6 + k];
        }
        out->p[i] = j->translation[i];
    }
}

/* motion from the parent frame into the child's: w = R^T w', v = R^T (v' - p x w') */
static void motion_to_child(const se3 *x, const double *m, double *out)
{
    double t[3];
    cross(x->p, &m[3], t);
    t[0] = m[0] - t[0];
    t[1] = m[1] - t[1];
    t[2] = m[2] - t[2];
    rotate_t(x->r, &m[3], &out[3]);
    rotate_t(x->r, t, out);
}

/* force from the child frame into the parent's: f' = R f, n' = R n + p x f' */
static void force_to_parent(const se3 *x, const double *f, double *out)
{
    double t[3];
    rotate(x->r, f, out);
    rotate(x->r, &f[3], &out[3]);
    cross(x->p, out, t);
    out[3] += t[0];
    out[4] += t[1];
    out[5] += t[2];
}

/* the spatial inertia (mass, lever c, inertia at the centre of mass) times a motion */
static void inertia_times(const orc_joint *j, const double *m, double *out)
{
    const double *c = j->lever, *ic = j->inertia; /* xx, xy, xz, yy, yz, zz */
    double cw[3], f[3], n[3], cf[3];
    int i;
    cross(c, &m[3], cw);
    for (i = 0; i < 3; i++) {
        f[i] = j->mass * (m[i] - cw[i]);
    }
    n[0] = ic[0] * m[3] + ic[1] * m[4] + ic[2] * m[5];
    n[1] = ic[1] * m[3] + ic[3] * m[4] + ic[4] * m[5];
    n[2] = ic[2] * m[3] + ic[4] * m[4] + ic[5] * m[5];
    cross(c, f, cf);
    for (i = 0; i < 3; i++) {
        out[i] = f[i];
        out[3 + i] = n[i] + cf[i];
    }
}

/* motion x motion: (v1, w1) x (v2, w2) = (w1 x v2 + v1 x w2, w1 x w2) */
static void cross_motion(const double *a, const double *b, double *out)
{
    double t1[3], t2[3], t3[3];
    int i;
    cross(&a[3], b, t1);
    cross(a, &b[3], t2);
    cross(&a[3], &b[3], t3);
    for (i = 0; i < 3; i++) {
        out[i] = t1[i] + t2[i];
        out[3 + i] = t3[i];
    }
}

/* motion x* force: (v, w) x* (f, n) = (w x f, w x n + v x f) */
static void cross_force(const double *a, const double *f, double *out)
{
    double t1[3], t2[3], t3[3];
    int i;
    cross(&a[3], f, t1);
    cross(&a[3], &f[3], t2);
    cross(a, f, t3);
    for (i = 0; i < 3; i++) {
        out[i] = t1[i];
        out[3 + i] = t2[i] + t3[i];
    }
}

static void subspace(const orc_joint *j, double *s)
{
    s[0] = s[1] = s[2] = 0.0;
    s[3] = j->axis[0];
    s[4] = j->axis[1];
    s[5] = j->axis[2];
}

static double dot6(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

void orc_nonlinear_effects(const orc_model *model, const double *q, const double *qdot,
                           double *out)
{
    se3 x[ORC_MAX_JOINTS];
    double v[ORC_MAX_JOINTS][6], a[ORC_MAX_JOINTS][6], f[ORC_MAX_JOINTS][6];
    int i, k, n = model->n;
    for (i = 0; i < n; i++) {
        const orc_joint *j = &model->joints[i];
        double s[6], vp[6] = {0.0}, ap[6] = {0.0}, t[6], iv[6];
        joint_transform(j, q[i], &x[i]);
        if (j->parent >= 0) {
            motion_to_child(&x[i], v[j->parent], vp);
            motion_to_child(&x[i], a[j->parent], ap);
        } else {
            ap[0] = -model->gravity[0]; /* the base accelerates against gravity */
            ap[1] = -model->gravity[1];
            ap[2] = -model->gravity[2];
            motion_to_child(&x[i], ap, ap);
        }
        subspace(j, s);
        for (k = 0; k < 6; k++) {
            v[i][k] = vp[k] + s[k] * qdot[i];
        }
        for (k = 0; k < 6; k++) {
            t[k] = s[k] * qdot[i];
        }
        cross_motion(v[i], t, t);
        for (k = 0; k < 6; k++) {
            a[i][k] = ap[k] + t[k];
        }
        inertia_times(j, a[i], f[i]);
        inertia_times(j, v[i], iv);
        cross_force(v[i], iv, t);
        for (k = 0; k < 6; k++) {
            f[i][k] += t[k];
        }
    }
    for (i = n - 1; i >= 0; i--) {
        const orc_joint *j = &model->joints[i];
        double s[6];
        subspace(j, s);
        out[i] = dot6(s, f[i]);
        if (j->parent >= 0) {
            double t[6];
            force_to_parent(&x[i], f[i], t);
            for (k = 0; k < 6; k++) {
                f[j->parent][k] += t[k];
            }
        }
    }
}

void orc_mass_matrix(const orc_model *model, const double *q, double *mass)
{
    /* M[i][k] = S_i . (the force of unit acceleration of joint k seen at i), by the
     * composite-body recursion written as forces carried up the chain (CRBA) */
    se3 x[ORC_MAX_JOINTS];
    int i, k, n = model->n;
    for (i = 0; i < n; i++) {
        joint_transform(&model->joints[i], q[i], &x[i]);
    }
    for (k = 0; k < n; k++) {
        /* the forces needed by a unit acceleration of joint k alone (no velocity, no
         * gravity): the bodies from k down the chain accelerate; forces sum upwards */
        double acc[ORC_MAX_JOINTS][6], force[ORC_MAX_JOINTS][6];
        int m;
        for (i = 0; i < n; i++) {
            const orc_joint *j = &model->joints[i];
            double ap[6] = {0.0}, s[6];
            if (j->parent >= 0) {
                motion_to_child(&x[i], acc[j->parent], ap);
            }
            subspace(j, s);
            for (m = 0; m < 6; m++) {
                acc[i][m] = ap[m] + (i == k ? s[m] : 0.0);
            }
            inertia_times(j, acc[i], force[i]);
        }
        for (i = n - 1; i >= 0; i--) {
            const orc_joint *j = &model->joints[i];
            double s[6];
            subspace(j, s);
            mass[i * n + k] = dot6(s, force[i]);
            if (j->parent >= 0) {
                double t[6];
                force_to_parent(&x[i], force[i], t);
                for (m = 0; m < 6; m++) {
                    force[j->parent][m] += t[m];
                }
            }
        }
    }
    for (i = 0; i < n; i++) { /* symmetric: the upper triangle mirrored, armature added */
        for (k = 0; k < i; k++) {
            mass[i * n + k] = mass[k * n + i];
        }
        mass[i * n + i] += model->joints[i].armature;
    }
}

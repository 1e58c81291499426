/* orccad_mt_laws.c: the control-law Module-Task kinds in C (pid, computed_torque,
 * dynamic_model, ct_feedback; orccad_app/control/laws), operation for operation the Python
 * kinds'. Part of the ORCCAD runtime library (the dispatch: orccad_mt.c); C99, no allocation,
 * no recursion. */
#include <string.h>

#include "orccad_dynamics.h"
#include "orccad_mt_kinds.h"

/* ---- parameter layouts (orccad_app/sil/generate/layout.py writes the same offsets) --------------- */
/* pid:       [dof, anti_windup, kp, kv, ki, tau_min, tau_max, alpha, beta (each [dof])]
 *            state: [t_prev set, t_prev, integral[dof], sat_dir[dof],
 *                    3 estimators (q velocity, qd velocity, qd_dot acceleration)] */
/* computed_torque, dynamic_model, ct_feedback: at each kind below. */

/* ---- backward differences (orccad_app/control/estimation.py) ---------------------------- */
/* state: [set, t, value[dim], derivative[dim]] = 2 + 2 dim doubles */

static const double *backward(double *st, int dim, double t_s, const double *value,
                              int on_change)
{
    double *last = &st[2], *deriv = &st[2 + dim];
    int i, same = 1;
    if (st[0] == 0.0) {
        st[0] = 1.0;
        st[1] = t_s;
        for (i = 0; i < dim; i++) {
            last[i] = value[i];
            deriv[i] = 0.0;
        }
        return deriv;
    }
    for (i = 0; i < dim; i++) {
        if (!(value[i] == last[i])) {
            same = 0;
        }
    }
    if (on_change && same) {
        return deriv;
    }
    if (t_s - st[1] > 0.0) {
        double dt = t_s - st[1];
        for (i = 0; i < dim; i++) {
            deriv[i] = (value[i] - last[i]) / dt;
            last[i] = value[i];
        }
        st[1] = t_s;
    }
    return deriv;
}

/* ---- PID (orccad_app/control/laws/fast.py, the plain-float path) ------------------------- */
/* the actuator constraint and the clamp of fast.py's _clamp; returns 1 if saturated */
static int clamp(int dof, const double *tau_unsat, const double *qdot, const double *bounds,
                 double *tau, double *sat_dir)
{
    int j, saturated = 0;
    for (j = 0; j < dof; j++) {
        double u = tau_unsat[j], v, lo, hi, d;
        orc_mt_torque_bounds(bounds, dof, j, qdot[j], &lo, &hi);
        v = u > lo ? u : lo;
        if (!(v < hi)) {
            v = hi;
        }
        tau[j] = v;
        d = u - v;
        if (sat_dir != NULL) {
            sat_dir[j] = d > 0 ? 1.0 : d < 0 ? -1.0 : 0.0;
        }
        saturated |= v != u;
    }
    return saturated;
}

/* inputs: qd, qd_dot, qd_ddot, q, qdot; outputs: tau, e, saturated */

void orc_mt_pid(orc_mt *m, double t_s)
{
    int dof = (int)m->p[0], j, ki_any = 0, any_sat = 0, integrate, windup, saturated = 0;
    int anti_windup = m->p[1] != 0.0;
    const double *kp = &m->p[2], *kv = &m->p[2 + dof], *ki = &m->p[2 + 2 * dof];
    const double *tau_min = &m->p[2 + 3 * dof]; /* the bounds: tau_min, tau_max, alpha, beta */
    double *integral = &m->s[2], *sat_dir = &m->s[2 + dof];
    double *est_q = &m->s[2 + 2 * dof], *est_r = est_q + 2 + 2 * dof;
    const double *pos, *vel, *q, *qdot;
    double dt, tau[ORC_MAX_DIM], e[ORC_MAX_DIM], flag, tau_unsat[ORC_MAX_DIM] = {0.0};
    if (!m->in[0].present) {
        return;
    }
    /* the reference's estimator sees every reference sample, even without q (as in
     * module_kinds.py: the reference is read before q is checked) */
    pos = m->in[0].v;
    vel = m->in[1].present ? m->in[1].v : backward(est_r, dof, t_s, pos, 1);
    if (!m->in[3].present) {
        return;
    }
    q = m->in[3].v;
    qdot = m->in[4].present ? m->in[4].v : backward(est_q, dof, t_s, q, 0);
    dt = 0.0;
    if (m->s[0] != 0.0) {
        dt = t_s - m->s[1];
        dt = 0.0 > dt ? 0.0 : dt;
    }
    m->s[0] = 1.0;
    m->s[1] = t_s;
    for (j = 0; j < dof; j++) {
        ki_any |= ki[j] != 0.0;
        any_sat |= sat_dir[j] != 0.0;
    }
    integrate = dt != 0.0 && ki_any;
    windup = integrate && anti_windup && any_sat;
    for (j = 0; j < dof; j++) {
        double x = q[j] - pos[j], u, d;
        e[j] = x;
        if (integrate) {
            d = x * dt;
            if (windup && -ki[j] * d * sat_dir[j] > 0) {
                d = 0.0;
            }
            integral[j] = integral[j] + d;
        }
        u = kp[j] * x + kv[j] * (qdot[j] - vel[j]);
        if (ki_any) {
            u = u + ki[j] * integral[j];
        }
        tau_unsat[j] = 0.0 - u;
    }
    saturated = clamp(dof, tau_unsat, qdot, tau_min, tau, sat_dir);
    orc_mt_set_out(m, 0, tau, dof);
    orc_mt_set_out(m, 1, e, dof);
    flag = saturated ? 1.0 : 0.0;
    orc_mt_set_out(m, 2, &flag, 1);
}

/* ---- computed torque (laws/fast.py's _model; multirate.py) ------------------------------- */
/* the model block: [gravity[3], per joint: parent, axis[3], rotation[9], translation[3],
 * mass, lever[3], inertia[6] (xx, xy, xz, yy, yz, zz), armature] */
#define JOINT_WORDS 27

static void load_model(const double *block, int n, orc_model *model)
{
    int i, k;
    model->n = n;
    for (k = 0; k < 3; k++) {
        model->gravity[k] = block[k];
    }
    for (i = 0; i < n && i < ORC_MAX_JOINTS; i++) {
        const double *w = &block[3 + i * JOINT_WORDS];
        orc_joint *j = &model->joints[i];
        j->parent = (int)w[0];
        memcpy(j->axis, &w[1], 3 * sizeof(double));
        memcpy(j->rotation, &w[4], 9 * sizeof(double));
        memcpy(j->translation, &w[13], 3 * sizeof(double));
        j->mass = w[16];
        memcpy(j->lever, &w[17], 3 * sizeof(double));
        memcpy(j->inertia, &w[20], 6 * sizeof(double));
        j->armature = w[26];
    }
}

/* computed_torque: [dof, feedforward, kp[n], kv[n], tau_min, tau_max, alpha, beta (each [n]),
 * damping[n], model block]; in qd, qd_dot, qd_ddot, q, qdot; out tau, e, saturated.
 * state as pid's, plus the reference acceleration's estimator */
void orc_mt_computed_torque(orc_mt *m, double t_s)
{
    int dof = (int)m->p[0], j, k;
    const double *kp = &m->p[2], *kv = &m->p[2 + dof], *bounds = &m->p[2 + 2 * dof];
    const double *damping = &m->p[2 + 6 * dof];
    double *sat_dir = &m->s[2 + dof];
    double *est_q = &m->s[2 + 2 * dof], *est_r = est_q + 2 + 2 * dof, *est_a = est_r + 2 + 2 * dof;
    const double *pos, *vel, *acc, *q, *qdot;
    double e[ORC_MAX_DIM] = {0.0}, feedback[ORC_MAX_DIM] = {0.0},
           mass[ORC_MAX_JOINTS * ORC_MAX_JOINTS] = {0.0};
    double bias[ORC_MAX_JOINTS] = {0.0}, tau_unsat[ORC_MAX_DIM] = {0.0}, tau[ORC_MAX_DIM] = {0.0};
    double flag;
    orc_model model;
    if (!m->in[0].present) {
        return;
    }
    pos = m->in[0].v;
    vel = m->in[1].present ? m->in[1].v : backward(est_r, dof, t_s, pos, 1);
    acc = m->in[2].present ? m->in[2].v : backward(est_a, dof, t_s, vel, 1);
    if (!m->in[3].present || dof > ORC_MAX_JOINTS) {
        return;
    }
    q = m->in[3].v;
    qdot = m->in[4].present ? m->in[4].v : backward(est_q, dof, t_s, q, 0);
    m->s[0] = 1.0;
    m->s[1] = t_s;
    load_model(&m->p[2 + 7 * dof], dof, &model);
    for (j = 0; j < dof; j++) {
        e[j] = q[j] - pos[j];
        feedback[j] = kp[j] * e[j] + kv[j] * (qdot[j] - vel[j]);
    }
    orc_mass_matrix(&model, q, mass);
    orc_nonlinear_effects(&model, q, qdot, bias);
    for (j = 0; j < dof; j++) {
        double product = 0.0, inertial = 0.0;
        for (k = 0; k < dof; k++) {
            product += -mass[j * dof + k] * feedback[k];
            inertial += mass[j * dof + k] * -acc[k];
        }
        tau_unsat[j] = product + (bias[j] + damping[j] * qdot[j]);
        if (m->p[1] != 0.0) {
            tau_unsat[j] = tau_unsat[j] - inertial;
        }
    }
    flag = clamp(dof, tau_unsat, qdot, bounds, tau, sat_dir) ? 1.0 : 0.0;
    orc_mt_set_out(m, 0, tau, dof);
    orc_mt_set_out(m, 1, e, dof);
    orc_mt_set_out(m, 2, &flag, 1);
}

/* dynamic_model: [dof, damping[n], model block]; in q, qdot; out M (n x n), N */
void orc_mt_dynamic_model(orc_mt *m)
{
    int dof = (int)m->p[0], j;
    double mass[ORC_MAX_JOINTS * ORC_MAX_JOINTS] = {0.0}, bias[ORC_MAX_JOINTS] = {0.0};
    orc_model model;
    if (!m->in[0].present || !m->in[1].present || dof > ORC_MAX_JOINTS
        || dof * dof > ORC_MAX_DIM) {
        return;
    }
    load_model(&m->p[1 + dof], dof, &model);
    orc_mass_matrix(&model, m->in[0].v, mass);
    orc_nonlinear_effects(&model, m->in[0].v, m->in[1].v, bias);
    for (j = 0; j < dof; j++) {
        bias[j] = bias[j] + m->p[1 + j] * m->in[1].v[j];
    }
    orc_mt_set_out(m, 0, mass, dof * dof);
    orc_mt_set_out(m, 1, bias, dof);
}

/* ct_feedback: [dof, kp[n], kv[n], tau_min, tau_max, alpha, beta]; in qd, qd_dot, qd_ddot,
 * q, qdot, M, N; out tau, e, saturated */
void orc_mt_ct_feedback(orc_mt *m)
{
    int dof = (int)m->p[0], j, k;
    const double *kp = &m->p[1], *kv = &m->p[1 + dof];
    double e[ORC_MAX_DIM] = {0.0}, u[ORC_MAX_DIM] = {0.0}, tau_unsat[ORC_MAX_DIM] = {0.0},
           tau[ORC_MAX_DIM] = {0.0}, flag;
    const double *qd, *qd_dot, *qd_ddot, *q, *qdot, *mass, *bias;
    for (j = 0; j < 7; j++) {
        if (!m->in[j].present) {
            return;
        }
    }
    qd = m->in[0].v;
    qd_dot = m->in[1].v;
    qd_ddot = m->in[2].v;
    q = m->in[3].v;
    qdot = m->in[4].v;
    mass = m->in[5].v;
    bias = m->in[6].v;
    for (j = 0; j < dof; j++) {
        e[j] = q[j] - qd[j];
    }
    for (j = 0; j < dof; j++) {
        u[j] = qd_ddot[j] - kp[j] * e[j] - kv[j] * (qdot[j] - qd_dot[j]);
    }
    for (j = 0; j < dof; j++) {
        double sum = 0.0;
        for (k = 0; k < dof; k++) {
            sum += mass[j * dof + k] * u[k];
        }
        tau_unsat[j] = sum + bias[j];
    }
    flag = clamp(dof, tau_unsat, qdot, &m->p[1 + 2 * dof], tau, NULL) ? 1.0 : 0.0;
    orc_mt_set_out(m, 0, tau, dof);
    orc_mt_set_out(m, 1, e, dof);
    orc_mt_set_out(m, 2, &flag, 1);
}

/* orccad_mt_observers.c: the observer Module-Task kinds in C (joint_limits,
 * torque_saturation, tracking_error, at_rest; plugins/orccad_observers), operation for
 * operation the Python kinds', and what every observer shares (edge, held). Part of the ORCCAD
 * runtime library (the dispatch: orccad_mt.c); C99, no allocation, no recursion. */
#include <math.h>

#include "orccad_mt_kinds.h"

/* ---- parameter layouts (orccad_app/sil/generate/layout.py writes the same offsets) --------------- */
/* observers: [edge, ...kind's parameters]             state: [held, t0 set, t0, ...] */
/* each kind's own parameters: at the kind below. */

/* ---- observers (plugins/orccad_observers/base.py: edge, held) ---------------------------- */

void orc_mt_observe(orc_mt *m, int holds, double value)
{
    int edge = m->p[0] != 0.0, fires = holds && !(edge && m->s[0] != 0.0);
    m->s[0] = holds ? 1.0 : 0.0;
    orc_mt_set_out1(m, 1, value);
    if (fires) {
        orc_mt_set_out1(m, 0, 1.0);
    }
}

/* np.min left to right keeping the later element on a tie (limits.py _least) */
static double least(const double *v, int n)
{
    double r = v[0];
    int i;
    for (i = 1; i < n; i++) {
        if (!(r < v[i])) {
            r = v[i];
        }
    }
    return r;
}

static double greatest(const double *v, int n)
{
    double r = v[0];
    int i;
    for (i = 1; i < n; i++) {
        if (!(r > v[i])) {
            r = v[i];
        }
    }
    return r;
}

/* joint_limits: [edge, margin, dof, lower[dof], upper[dof]]; in q */
void orc_mt_joint_limits(orc_mt *m)
{
    int dof = (int)m->p[2], j;
    double nearest[ORC_MAX_DIM] = {0.0};
    if (!m->in[0].present) {
        return;
    }
    for (j = 0; j < dof; j++) {
        double below = m->in[0].v[j] - m->p[3 + j], above = m->p[3 + dof + j] - m->in[0].v[j];
        nearest[j] = below < above ? below : above;
    }
    {
        double distance = least(nearest, dof);
        orc_mt_observe(m, distance < m->p[1], distance);
    }
}

/* torque_saturation: [edge, ratio, dof, tau_min, tau_max, alpha, beta]; in tau, qdot */
void orc_mt_torque_saturation(orc_mt *m)
{
    int dof = (int)m->p[2], j;
    double usage[ORC_MAX_DIM] = {0.0}, peak;
    if (!m->in[0].present) {
        return;
    }
    for (j = 0; j < dof; j++) {
        double tau = m->in[0].v[j], qdot = m->in[1].present ? m->in[1].v[j] : 0.0, low, high;
        orc_mt_torque_bounds(&m->p[3], dof, j, qdot, &low, &high);
        if (tau > 0) {
            usage[j] = high > 0 ? tau / high : HUGE_VAL;
        } else if (tau < 0) {
            usage[j] = low < 0 ? tau / low : HUGE_VAL;
        } else {
            usage[j] = 0.0;
        }
    }
    peak = greatest(usage, dof);
    orc_mt_observe(m, peak >= m->p[1] - 1e-9, peak);
}

/* max |x| (motion.py _norm: np.max(np.abs(x)); exact in any order for finite values) */
static double norm_inf(const double *x, int n)
{
    double r = fabs(x[0]);
    int i;
    for (i = 1; i < n; i++) {
        double a = fabs(x[i]);
        if (!(r > a)) {
            r = a;
        }
    }
    return r;
}

/* tracking_error: [edge, max, dim]; in e, q, qd */
void orc_mt_tracking_error(orc_mt *m)
{
    int dim = (int)m->p[2], i;
    double diff[ORC_MAX_DIM] = {0.0}, value;
    if (m->in[0].present) {
        value = norm_inf(m->in[0].v, dim);
    } else {
        if (!m->in[1].present || !m->in[2].present) {
            return;
        }
        for (i = 0; i < dim; i++) {
            diff[i] = m->in[1].v[i] - m->in[2].v[i];
        }
        value = norm_inf(diff, dim);
    }
    orc_mt_observe(m, value > m->p[1], value);
}

/* at_rest: [edge, tol, dim]; in qdot */
void orc_mt_at_rest(orc_mt *m)
{
    double value;
    if (!m->in[0].present) {
        return;
    }
    value = norm_inf(m->in[0].v, (int)m->p[2]);
    orc_mt_observe(m, value <= m->p[1], value);
}

/* observers.c: the C of the observers plugin's joint_limits, torque_saturation,
 * tracking_error and at_rest (plugins/orccad_observers/limits.py, motion.py), operation for
 * operation the Python kinds', so that the values agree on finite inputs (orccad sil
 * --check-kinds; tests/sil/test_kinds.py). Each kind's parameter words are its
 * CImplementation.params (plugins/orccad_observers/c_kinds.py), in the order of its layout
 * comment below; every observer's first word is its edge flag and its state's first word
 * "held" (orc_mt_observe). C99, no allocation, no recursion (docs/deploy.md, "A plugin kind's
 * C"). */
#include <math.h>

#include "orccad_mt.h"

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
void orccad_obs_joint_limits_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state */
}

void orccad_obs_joint_limits_compute(orc_mt *m, double t_s)
{
    int dof = (int)m->p[2], j;
    double nearest[ORC_MAX_DIM] = {0.0};
    (void)t_s;
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
void orccad_obs_torque_saturation_init(orc_mt *m)
{
    (void)m;
}

void orccad_obs_torque_saturation_compute(orc_mt *m, double t_s)
{
    int dof = (int)m->p[2], j;
    double usage[ORC_MAX_DIM] = {0.0}, peak;
    (void)t_s;
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
void orccad_obs_tracking_error_init(orc_mt *m)
{
    (void)m;
}

void orccad_obs_tracking_error_compute(orc_mt *m, double t_s)
{
    int dim = (int)m->p[2], i;
    double diff[ORC_MAX_DIM] = {0.0}, value;
    (void)t_s;
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
void orccad_obs_at_rest_init(orc_mt *m)
{
    (void)m;
}

void orccad_obs_at_rest_compute(orc_mt *m, double t_s)
{
    double value;
    (void)t_s;
    if (!m->in[0].present) {
        return;
    }
    value = norm_inf(m->in[0].v, (int)m->p[2]);
    orc_mt_observe(m, value <= m->p[1], value);
}

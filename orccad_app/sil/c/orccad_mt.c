/* orccad_mt.c: the Module-Tasks of ORCCAD in C: an instance's lifecycle (load, init, one
 * compute, a type-1 parameter update), the dispatch of a job to its kind, and what every kind
 * uses to write its outputs and read its task time (orccad_mt_kinds.h).
 *
 * The kinds of the control library, each operation for operation its Python kind
 * (orccad_app/control) so that the values are bit-identical on finite
 * inputs (tests/sil/test_kinds.py compares them), with its parameter and state layout
 * (orccad_app/sil/generate/layout.py writes the same offsets):
 *   orccad_mt_trajectory.c  cosine, min_jerk, constant
 *   orccad_mt_laws.c        pid, computed_torque, dynamic_model, ct_feedback
 * A plugin's kind (the observers', plugins/orccad_observers/c; the AUV's, plugins/orccad_auv/c;
 * a third party's) is the generated table's (orc_plugin_compute). Ties follow numpy's rules
 * where the Python code uses numpy (np.maximum(a, b) and np.minimum(a, b) return b on a tie)
 * and Python's where it uses min()/max().
 * C99, no allocation, no recursion. */
#include <string.h>

#include "orccad_mt_kinds.h"

/* ---- what the kinds share (orccad_mt.h: the plugins' kinds too) ------------------------ */

void orc_mt_set_out(orc_mt *m, int slot, const double *v, int dim)
{
    int i;
    m->out[slot].present = 1;
    m->out[slot].dim = dim;
    for (i = 0; i < dim; i++) {
        m->out[slot].v[i] = v[i];
    }
}

void orc_mt_set_out1(orc_mt *m, int slot, double v)
{
    orc_mt_set_out(m, slot, &v, 1);
}

void orc_mt_torque_bounds(const double *bounds, int dof, int j, double qdot, double *lo,
                          double *hi)
{
    const double *tau_min = bounds, *tau_max = bounds + dof, *alpha = bounds + 2 * dof,
                 *beta = bounds + 3 * dof;
    double back_emf = beta[j] == 0.0 ? 0.0 : beta[j] * qdot, floor;
    *lo = -alpha[j] - back_emf;
    if (tau_min[j] > *lo) {
        *lo = tau_min[j];
    }
    *hi = alpha[j] - back_emf;
    if (tau_max[j] < *hi) {
        *hi = tau_max[j];
    }
    floor = *lo < tau_max[j] ? *lo : tau_max[j];
    if (!(*hi > floor)) {
        *hi = floor;
    }
    if (!(*lo < *hi)) {
        *lo = *hi;
    }
}

/* ModuleInstance.task_time: seconds since the first job after init. */
double orc_mt_task_time(double *state, double t_s)
{
    if (state[0] == 0.0) {
        state[0] = 1.0;
        state[1] = t_s;
    }
    return t_s - state[1];
}

void orc_mt_observe(orc_mt *m, int holds, double value)
{
    int edge = m->p[0] != 0.0, fires = holds && !(edge && m->s[0] != 0.0);
    m->s[0] = holds ? 1.0 : 0.0;
    orc_mt_set_out1(m, 1, value);
    if (fires) {
        orc_mt_set_out1(m, 0, 1.0);
    }
}

/* ---- the interface ----------------------------------------------------------------------- */

void orc_mt_load(orc_mt *m, const orc_mt_def *def)
{
    int i;
    memset(m, 0, sizeof *m);
    m->def = def;
    m->kind = def->kind;
    m->n_in = def->n_in;
    m->n_out = def->n_out;
    for (i = 0; i < def->n_params && i < ORC_MAX_PARAMS; i++) {
        m->p[i] = def->params[i];
    }
    for (i = 0; i < ORC_MAX_PORTS; i++) {
        m->in[i].dim = def->in_dim[i];
        m->out[i].dim = def->out_dim[i];
    }
}

void orc_mt_init(orc_mt *m)
{
    int i;
    for (i = 0; i < ORC_MAX_STATE; i++) {
        m->s[i] = 0.0;
    }
    if (m->kind >= ORC_PLUGIN_BASE) {
        (void)orc_plugin_init(m);
    }
}

int orc_mt_compute(orc_mt *m, double t_s)
{
    int i;
    for (i = 0; i < m->n_out; i++) {
        m->out[i].present = 0;
    }
    switch (m->kind) {
    case ORC_TRAJ_COSINE: orc_mt_cosine(m, t_s); break;
    case ORC_TRAJ_MIN_JERK: orc_mt_min_jerk(m, t_s); break;
    case ORC_TRAJ_CONSTANT: orc_mt_constant(m, t_s); break;
    case ORC_LAW_PID: orc_mt_pid(m, t_s); break;
    case ORC_LAW_CT: orc_mt_computed_torque(m, t_s); break;
    case ORC_MODEL_DYN: orc_mt_dynamic_model(m); break;
    case ORC_CT_FEEDBACK: orc_mt_ct_feedback(m); break;
    default: return orc_plugin_compute(m, t_s);
    }
    return 0;
}

int orc_mt_set_param(orc_mt *m, int offset, const double *values, int n)
{
    int i;
    if (offset < 0 || n < 0 || offset + n > ORC_MAX_PARAMS) {
        return -1;
    }
    for (i = 0; i < n; i++) {
        m->p[offset + i] = values[i];
    }
    return 0;
}
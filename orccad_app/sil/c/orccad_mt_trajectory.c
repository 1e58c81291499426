/* orccad_mt_trajectory.c: the trajectory Module-Task kinds in C (cosine, min_jerk, constant;
 * orccad_app/control's trajectories), operation for operation the Python kinds'. Part of the
 * ORCCAD runtime library (the dispatch: orccad_mt.c); C99, no allocation, no recursion. */
#include <math.h>

#include "orccad_mt_kinds.h"

/* ---- parameter layouts (orccad_app/sil/generate/layout.py writes the same offsets) --------------- */
/* cosine:    [dim, omega, q0[dim]]                     state: [t0 set, t0] */
/* min_jerk:  [dim, duration, has_start, goal[dim], start[dim]]
 *                                                      state: [t0 set, t0, started, start[dim]] */
/* constant:  [dim, has_value, value[dim]]              state: [t0 set, t0, started, value[dim]] */

#define TRAJ_POS 0
#define TRAJ_VEL 1
#define TRAJ_ACC 2

void orc_mt_cosine(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0], i;
    double omega = m->p[1], t = orc_mt_task_time(m->s, t_s);
    double phase = omega * t, c = cos(phase), s = sin(phase), pos[ORC_MAX_DIM],
           vel[ORC_MAX_DIM], acc[ORC_MAX_DIM];
    for (i = 0; i < dim; i++) {
        double q0 = m->p[2 + i];
        pos[i] = q0 * (1.0 + c);
        vel[i] = (-q0 * omega) * s;
        acc[i] = (-q0 * pow(omega, 2.0)) * c;
    }
    orc_mt_set_out(m, TRAJ_POS, pos, dim);
    orc_mt_set_out(m, TRAJ_VEL, vel, dim);
    orc_mt_set_out(m, TRAJ_ACC, acc, dim);
}

/* The start position: given, or the first measured q (input slot 0). 0: none yet. */
static int traj_start(orc_mt *m, int has_given, const double *given, int dim)
{
    int i;
    double *start = &m->s[3];
    if (m->s[2] != 0.0) {
        return 1;
    }
    if (has_given) {
        for (i = 0; i < dim; i++) {
            start[i] = given[i];
        }
    } else {
        if (m->n_in < 1 || !m->in[0].present) {
            return 0;
        }
        for (i = 0; i < dim; i++) {
            start[i] = m->in[0].v[i];
        }
    }
    m->s[2] = 1.0;
    return 1;
}

void orc_mt_min_jerk(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0], i;
    double duration = m->p[1], *goal = &m->p[3], *start = &m->s[3];
    double tau, s, ds, dds, pos[ORC_MAX_DIM], vel[ORC_MAX_DIM], acc[ORC_MAX_DIM];
    if (!traj_start(m, m->p[2] != 0.0, &m->p[3 + dim], dim)) {
        return;
    }
    tau = orc_mt_task_time(m->s, t_s) / duration;
    tau = 0.0 > tau ? 0.0 : tau;     /* Python max(x, 0.0): x unless 0.0 > x */
    tau = 1.0 < tau ? 1.0 : tau;     /* Python min(x, 1.0): x unless 1.0 < x */
    s = pow(tau, 3.0) * (10.0 - 15.0 * tau + 6.0 * pow(tau, 2.0));
    ds = 30.0 * pow(tau, 2.0) * pow(1.0 - tau, 2.0) / duration;
    dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau) / pow(duration, 2.0);
    for (i = 0; i < dim; i++) {
        double delta = goal[i] - start[i];
        pos[i] = start[i] + s * delta;
        vel[i] = ds * delta;
        acc[i] = dds * delta;
    }
    orc_mt_set_out(m, TRAJ_POS, pos, dim);
    orc_mt_set_out(m, TRAJ_VEL, vel, dim);
    orc_mt_set_out(m, TRAJ_ACC, acc, dim);
}

void orc_mt_constant(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0];
    double zero[ORC_MAX_DIM] = {0.0};
    if (!traj_start(m, m->p[1] != 0.0, &m->p[2], dim)) {
        return;
    }
    (void)orc_mt_task_time(m->s, t_s);
    orc_mt_set_out(m, TRAJ_POS, &m->s[3], dim);
    orc_mt_set_out(m, TRAJ_VEL, zero, dim);
    orc_mt_set_out(m, TRAJ_ACC, zero, dim);
}

/* auv_autopilot.c: the C of the AUV plugin's autopilot (auv_autopilot) (plugins/orccad_auv/control.py), operation for
 * operation the Python kind's, so that the values agree on finite inputs (orccad sil
 * --check-kinds; tests/sil/test_kinds.py). Its parameter words are the kind's
 * CImplementation.params (plugins/orccad_auv/c_kinds.py), in the order of the layout below.
 * C99, no allocation, no recursion (docs/deploy.md, "A plugin kind's C"). */
#include <math.h>

#include "orccad_mt.h"

static double wrap(double angle)
{
    return atan2(sin(angle), cos(angle));
}

/* Python's min(a, max(b, x)) */
static double py_clamp(double x, double low, double high)
{
    double r = x > low ? x : low;   /* max(low, x): low unless x > low */
    return r < high ? r : high;     /* min(high, r): high unless r < high */
}

/* autopilot: [kp_depth, kd_depth, ki_depth, max_integral, max_heave, kp_pitch, kd_pitch,
 *             kp_heading, kd_heading, k_speed, drag_coeff, arm, limits[5]]
 * in setpoint[4], depth, attitude[3], velocity[6]; out tau[5]; state [last set, last t,
 * integral] */
void orccad_auv_autopilot_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state */
}

void orccad_auv_autopilot_compute(orc_mt *m, double t_s)
{
    const double *p = m->p, *sp, *att, *vel;
    double depth, dt, w_up, error, bound, force, heave, pitch, yaw, surge, sway, f[5];
    int i;
    for (i = 0; i < 4; i++) {
        if (!m->in[i].present) {
            return;
        }
    }
    sp = m->in[0].v;
    depth = m->in[1].v[0];
    att = m->in[2].v;
    vel = m->in[3].v;
    dt = m->s[0] == 0.0 ? 0.0 : t_s - m->s[1];
    m->s[0] = 1.0;
    m->s[1] = t_s;
    w_up = -sin(att[1]) * vel[0] + cos(att[1]) * sin(att[0]) * vel[1]
           + cos(att[1]) * cos(att[0]) * vel[2];
    error = depth - sp[0];
    bound = p[3];
    {
        double x = m->s[2] + p[2] * error * dt, lowered;
        lowered = x > -bound ? x : -bound;          /* max(-bound, x) */
        m->s[2] = lowered < bound ? lowered : bound; /* min(bound, .) */
    }
    force = p[0] * error - p[1] * w_up + m->s[2];
    heave = py_clamp(force, -p[4], p[4]);
    pitch = -p[5] * att[1] - p[6] * vel[4];
    yaw = p[7] * wrap(sp[1] - att[2]) - p[8] * vel[5];
    surge = p[9] * (sp[2] - vel[0]) + p[10] * sp[2] * fabs(sp[2]);
    sway = p[9] * (sp[3] - vel[1]);
    f[0] = surge;
    f[1] = (heave - pitch / p[11]) / 2.0;
    f[2] = (heave + pitch / p[11]) / 2.0;
    f[3] = (sway + yaw / p[11]) / 2.0;
    f[4] = (sway - yaw / p[11]) / 2.0;
    for (i = 0; i < 5; i++) {  /* np.clip: minimum(maximum(f, -L), L) */
        double lo = -p[12 + i], v = f[i];
        v = v > lo ? v : lo;
        if (!(v < p[12 + i])) {
            v = p[12 + i];
        }
        f[i] = v;
    }
    orc_mt_set_out(m, 0, f, 5);
}

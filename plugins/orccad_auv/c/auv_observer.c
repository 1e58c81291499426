/* auv_observer.c: the C of the AUV plugin's observers (battery_low, altitude_low, at_waypoint, leak, depth_limit, gps_fix) (plugins/orccad_auv/observers.py), operation for
 * operation the Python kind's, so that the values agree on finite inputs (orccad sil
 * --check-kinds; tests/sil/test_kinds.py). Its parameter words are the kind's
 * CImplementation.params (plugins/orccad_auv/c_kinds.py), in the order of the layout below.
 * C99, no allocation, no recursion (docs/deploy.md, "A plugin kind's C"). */
#include <math.h>

#include "orccad_mt.h"

/* AUV observers: [edge, limit, mode]; mode 0: value < limit, 1: value > limit, 2: a GPS fix
 * held for limit [s]. in slot 0. state [held, t0 set, t0, since set, since] */
void orccad_auv_observer_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state */
}

void orccad_auv_observer_compute(orc_mt *m, double t_s)
{
    double value, t;
    int mode = (int)m->p[2];
    if (!m->in[0].present) {
        return;
    }
    value = m->in[0].v[0];
    if (mode == 0) {
        orc_mt_observe(m, value < m->p[1], value);
        return;
    }
    if (mode == 1) {
        orc_mt_observe(m, value > m->p[1], value);
        return;
    }
    t = orc_mt_task_time(&m->s[1], t_s);
    if (value < 0.5) {
        m->s[3] = 0.0;
        orc_mt_observe(m, 0, 0.0);
        return;
    }
    if (m->s[3] == 0.0) {
        m->s[3] = 1.0;
        m->s[4] = t;
    }
    orc_mt_observe(m, t - m->s[4] >= m->p[1], t - m->s[4]);
}

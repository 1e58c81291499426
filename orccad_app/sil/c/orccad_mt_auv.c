/* orccad_mt_auv.c: the AUV's Module-Task kinds in C (autopilot, guidance, observers;
 * plugins/orccad_auv/control.py, observers.py), operation for operation the Python kinds'.
 * Part of the ORCCAD runtime library (the dispatch: orccad_mt.c); C99, no allocation, no
 * recursion. Each kind's parameter layout (orccad_app/sil/generate/layout.py writes the same offsets)
 * is at the kind. */
#include <math.h>

#include "orccad_mt_kinds.h"

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
void orc_mt_autopilot(orc_mt *m, double t_s)
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

/* guidance: [mode, depth, speed, x, y, gain, max_speed, radius, lookahead, n_points,
 *            points (x, y) * n]; mode 0 depth, 1 station, 2 line of sight.
 * in position[3], attitude[3]; out setpoint[4], goal_error[1].
 * state: [heading set, heading, index set, index, start x, start y] */
#define GUIDE_POINTS 10
#define GUIDE_FAR_M 1e9

static double dist2(double ax, double ay, double bx, double by)
{
    return hypot(ax - bx, ay - by);
}

void orc_mt_guidance(orc_mt *m)
{
    const double *p = m->p, *pos, *att, *pts = &m->p[GUIDE_POINTS];
    double yaw, sp[4], goal;
    int mode = (int)p[0];
    if (!m->in[0].present || !m->in[1].present) {
        return;
    }
    pos = m->in[0].v;
    att = m->in[1].v;
    yaw = att[2];
    if (m->s[0] == 0.0) {
        m->s[0] = 1.0;
        m->s[1] = yaw;
    }
    if (mode == 0) {
        sp[0] = p[1];
        sp[1] = m->s[1];
        sp[2] = p[2];
        sp[3] = 0.0;
        goal = fabs(pos[2] - p[1]);
    } else if (mode == 1) {
        double ex = p[3] - pos[0], ey = p[4] - pos[1], wx = p[5] * ex, wy = p[5] * ey;
        double norm = sqrt(wx * wx + wy * wy), c = cos(yaw), s = sin(yaw);
        if (norm > p[6]) {
            double scale = p[6] / norm;
            wx *= scale;
            wy *= scale;
        }
        sp[0] = p[1];
        sp[1] = m->s[1];
        sp[2] = c * wx + s * wy;
        sp[3] = -s * wx + c * wy;
        goal = hypot(sqrt(ex * ex + ey * ey), pos[2] - p[1]);
    } else {
        int n = (int)p[9], last = n - 1, index, i;
        double hx = pos[0], hy = pos[1], ax, ay, bx, by, lx, ly, length, heading, to_go, speed;
        if (m->s[2] == 0.0) {  /* start (or resume) at the nearest waypoint: np.argmin */
            double best = dist2(hx, hy, pts[0], pts[1]);
            int arg = 0;
            for (i = 1; i < n; i++) {
                double d = dist2(hx, hy, pts[2 * i], pts[2 * i + 1]);
                if (d < best) {
                    best = d;
                    arg = i;
                }
            }
            m->s[2] = 1.0;
            m->s[3] = arg;
            m->s[4] = hx;
            m->s[5] = hy;
        }
        index = (int)m->s[3];
        while (index < last && dist2(hx, hy, pts[2 * index], pts[2 * index + 1]) < p[7]) {
            m->s[4] = pts[2 * index];
            m->s[5] = pts[2 * index + 1];
            index++;
        }
        m->s[3] = index;
        ax = m->s[4];
        ay = m->s[5];
        bx = pts[2 * index];
        by = pts[2 * index + 1];
        lx = bx - ax;
        ly = by - ay;
        length = sqrt(lx * lx + ly * ly);
        if (length < 1e-6) {
            heading = atan2(by - hy, bx - hx);
        } else {
            double tx = lx / length, ty = ly / length, dx = hx - ax, dy = hy - ay;
            double cross = tx * dy - ty * dx;
            heading = atan2(ty, tx) - atan(cross / p[8]);
        }
        to_go = dist2(hx, hy, bx, by);
        speed = p[2];
        goal = GUIDE_FAR_M;
        if (index == last) {
            double slow = 0.25 * to_go + 0.1;
            speed = slow < speed ? slow : speed;  /* min(speed, slow) */
            goal = hypot(to_go, pos[2] - p[1]);
        }
        sp[0] = p[1];
        sp[1] = heading;
        sp[2] = speed;
        sp[3] = 0.0;
    }
    orc_mt_set_out(m, 0, sp, 4);
    orc_mt_set_out1(m, 1, goal);
}

/* AUV observers: [edge, limit, mode]; mode 0: value < limit, 1: value > limit, 2: a GPS fix
 * held for limit [s]. in slot 0. state [held, t0 set, t0, since set, since] */
void orc_mt_auv_observer(orc_mt *m, double t_s)
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

/* auv_guidance.c: the C of the AUV plugin's guidance kinds (depth, station, hold, line of sight, waypoint, lawnmower) (plugins/orccad_auv/control.py), operation for
 * operation the Python kind's, so that the values agree on finite inputs (orccad sil
 * --check-kinds; tests/sil/test_kinds.py). Its parameter words are the kind's
 * CImplementation.params (plugins/orccad_auv/c_kinds.py), in the order of the layout below.
 * C99, no allocation, no recursion (docs/deploy.md, "A plugin kind's C"). */
#include <math.h>

#include "orccad_mt.h"

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

void orccad_auv_guidance_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state */
}

void orccad_auv_guidance_compute(orc_mt *m, double t_s)
{
    const double *p = m->p, *pos, *att, *pts = &m->p[GUIDE_POINTS];
    double yaw, sp[4], goal;
    int mode = (int)p[0];
    (void)t_s;
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

/* orccad_mt.c: the Module-Task kinds of ORCCAD in C, operation for operation the Python
 * kinds' (orccad_app/control, plugins/orccad_observers, plugins/orccad_auv), so that the
 * values are bit-identical on finite inputs (tests/sil/test_kinds.py compares them).
 * Ties follow numpy's rules where the Python code uses numpy (np.maximum(a, b) and
 * np.minimum(a, b) return b on a tie) and Python's where it uses min()/max().
 * C99, no allocation, no recursion. */
#include <math.h>
#include <string.h>

#include "orccad_dynamics.h"
#include "orccad_mt.h"

/* ---- parameter layouts (orccad_app/sil/layout.py writes the same offsets) --------------- */
/* cosine:    [dim, omega, q0[dim]]                     state: [t0 set, t0] */
/* min_jerk:  [dim, duration, has_start, goal[dim], start[dim]]
 *                                                      state: [t0 set, t0, started, start[dim]] */
/* constant:  [dim, has_value, value[dim]]              state: [t0 set, t0, started, value[dim]] */
/* pid:       [dof, anti_windup, kp, kv, ki, tau_min, tau_max, alpha, beta (each [dof])]
 *            state: [t_prev set, t_prev, integral[dof], sat_dir[dof],
 *                    3 estimators (q velocity, qd velocity, qd_dot acceleration)] */
/* observers: [edge, ...kind's parameters]             state: [held, t0 set, t0, ...] */

#define TRAJ_POS 0
#define TRAJ_VEL 1
#define TRAJ_ACC 2

static void set_out(orc_mt *m, int slot, const double *v, int dim)
{
    int i;
    m->out[slot].present = 1;
    m->out[slot].dim = dim;
    for (i = 0; i < dim; i++) {
        m->out[slot].v[i] = v[i];
    }
}

static void set_out1(orc_mt *m, int slot, double v)
{
    set_out(m, slot, &v, 1);
}

/* ModuleInstance.task_time: seconds since the first job after init. */
static double task_time(double *state, double t_s)
{
    if (state[0] == 0.0) {
        state[0] = 1.0;
        state[1] = t_s;
    }
    return t_s - state[1];
}

/* ---- trajectories ------------------------------------------------------------------------ */

static void cosine(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0], i;
    double omega = m->p[1], t = task_time(m->s, t_s);
    double phase = omega * t, c = cos(phase), s = sin(phase), pos[ORC_MAX_DIM],
           vel[ORC_MAX_DIM], acc[ORC_MAX_DIM];
    for (i = 0; i < dim; i++) {
        double q0 = m->p[2 + i];
        pos[i] = q0 * (1.0 + c);
        vel[i] = (-q0 * omega) * s;
        acc[i] = (-q0 * pow(omega, 2.0)) * c;
    }
    set_out(m, TRAJ_POS, pos, dim);
    set_out(m, TRAJ_VEL, vel, dim);
    set_out(m, TRAJ_ACC, acc, dim);
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

static void min_jerk(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0], i;
    double duration = m->p[1], *goal = &m->p[3], *start = &m->s[3];
    double tau, s, ds, dds, pos[ORC_MAX_DIM], vel[ORC_MAX_DIM], acc[ORC_MAX_DIM];
    if (!traj_start(m, m->p[2] != 0.0, &m->p[3 + dim], dim)) {
        return;
    }
    tau = task_time(m->s, t_s) / duration;
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
    set_out(m, TRAJ_POS, pos, dim);
    set_out(m, TRAJ_VEL, vel, dim);
    set_out(m, TRAJ_ACC, acc, dim);
}

static void constant(orc_mt *m, double t_s)
{
    int dim = (int)m->p[0];
    double zero[ORC_MAX_DIM] = {0.0};
    if (!traj_start(m, m->p[1] != 0.0, &m->p[2], dim)) {
        return;
    }
    (void)task_time(m->s, t_s);
    set_out(m, TRAJ_POS, &m->s[3], dim);
    set_out(m, TRAJ_VEL, zero, dim);
    set_out(m, TRAJ_ACC, zero, dim);
}

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
    const double *tau_min = bounds, *tau_max = bounds + dof, *alpha = bounds + 2 * dof,
                 *beta = bounds + 3 * dof;
    int j, saturated = 0;
    for (j = 0; j < dof; j++) {
        double u = tau_unsat[j], v, lo, hi, floor, back_emf, d;
        back_emf = beta[j] == 0.0 ? 0.0 : beta[j] * qdot[j];
        lo = -alpha[j] - back_emf;
        if (tau_min[j] > lo) {
            lo = tau_min[j];
        }
        hi = alpha[j] - back_emf;
        if (tau_max[j] < hi) {
            hi = tau_max[j];
        }
        floor = lo < tau_max[j] ? lo : tau_max[j];
        if (!(hi > floor)) {
            hi = floor;
        }
        if (!(lo < hi)) {
            lo = hi;
        }
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

static void pid(orc_mt *m, double t_s)
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
    set_out(m, 0, tau, dof);
    set_out(m, 1, e, dof);
    flag = saturated ? 1.0 : 0.0;
    set_out(m, 2, &flag, 1);
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
static void computed_torque(orc_mt *m, double t_s)
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
    set_out(m, 0, tau, dof);
    set_out(m, 1, e, dof);
    set_out(m, 2, &flag, 1);
}

/* dynamic_model: [dof, damping[n], model block]; in q, qdot; out M (n x n), N */
static void dynamic_model(orc_mt *m)
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
    set_out(m, 0, mass, dof * dof);
    set_out(m, 1, bias, dof);
}

/* ct_feedback: [dof, kp[n], kv[n], tau_min, tau_max, alpha, beta]; in qd, qd_dot, qd_ddot,
 * q, qdot, M, N; out tau, e, saturated */
static void ct_feedback(orc_mt *m)
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
    set_out(m, 0, tau, dof);
    set_out(m, 1, e, dof);
    set_out(m, 2, &flag, 1);
}

/* ---- observers (plugins/orccad_observers/base.py: edge, held) ---------------------------- */

static void observe(orc_mt *m, int holds, double value)
{
    int edge = m->p[0] != 0.0, fires = holds && !(edge && m->s[0] != 0.0);
    m->s[0] = holds ? 1.0 : 0.0;
    set_out1(m, 1, value);
    if (fires) {
        set_out1(m, 0, 1.0);
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
static void joint_limits(orc_mt *m)
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
        observe(m, distance < m->p[1], distance);
    }
}

/* torque_saturation: [edge, ratio, dof, tau_min, tau_max, alpha, beta]; in tau, qdot */
static void torque_saturation(orc_mt *m)
{
    int dof = (int)m->p[2], j;
    const double *tau_min = &m->p[3], *tau_max = &m->p[3 + dof], *alpha = &m->p[3 + 2 * dof],
                 *beta = &m->p[3 + 3 * dof];
    double usage[ORC_MAX_DIM] = {0.0}, peak;
    if (!m->in[0].present) {
        return;
    }
    for (j = 0; j < dof; j++) {
        double tau = m->in[0].v[j], qdot = m->in[1].present ? m->in[1].v[j] : 0.0;
        double back_emf = beta[j] == 0.0 ? 0.0 : beta[j] * qdot, low, high, floor;
        low = -alpha[j] - back_emf;
        if (tau_min[j] > low) {
            low = tau_min[j];
        }
        high = alpha[j] - back_emf;
        if (tau_max[j] < high) {
            high = tau_max[j];
        }
        floor = low < tau_max[j] ? low : tau_max[j];
        if (!(high > floor)) {
            high = floor;
        }
        if (!(low < high)) {
            low = high;
        }
        if (tau > 0) {
            usage[j] = high > 0 ? tau / high : HUGE_VAL;
        } else if (tau < 0) {
            usage[j] = low < 0 ? tau / low : HUGE_VAL;
        } else {
            usage[j] = 0.0;
        }
    }
    peak = greatest(usage, dof);
    observe(m, peak >= m->p[1] - 1e-9, peak);
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
static void tracking_error(orc_mt *m)
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
    observe(m, value > m->p[1], value);
}

/* at_rest: [edge, tol, dim]; in qdot */
static void at_rest(orc_mt *m)
{
    double value;
    if (!m->in[0].present) {
        return;
    }
    value = norm_inf(m->in[0].v, (int)m->p[2]);
    observe(m, value <= m->p[1], value);
}

/* ---- the AUV (plugins/orccad_auv/control.py, observers.py) ------------------------------- */

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
static void autopilot(orc_mt *m, double t_s)
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
    set_out(m, 0, f, 5);
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

static void guidance(orc_mt *m)
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
    set_out(m, 0, sp, 4);
    set_out1(m, 1, goal);
}

/* AUV observers: [edge, limit, mode]; mode 0: value < limit, 1: value > limit, 2: a GPS fix
 * held for limit [s]. in slot 0. state [held, t0 set, t0, since set, since] */
static void auv_observer(orc_mt *m, double t_s)
{
    double value, t;
    int mode = (int)m->p[2];
    if (!m->in[0].present) {
        return;
    }
    value = m->in[0].v[0];
    if (mode == 0) {
        observe(m, value < m->p[1], value);
        return;
    }
    if (mode == 1) {
        observe(m, value > m->p[1], value);
        return;
    }
    t = task_time(&m->s[1], t_s);
    if (value < 0.5) {
        m->s[3] = 0.0;
        observe(m, 0, 0.0);
        return;
    }
    if (m->s[3] == 0.0) {
        m->s[3] = 1.0;
        m->s[4] = t;
    }
    observe(m, t - m->s[4] >= m->p[1], t - m->s[4]);
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
    case ORC_TRAJ_COSINE: cosine(m, t_s); break;
    case ORC_TRAJ_MIN_JERK: min_jerk(m, t_s); break;
    case ORC_TRAJ_CONSTANT: constant(m, t_s); break;
    case ORC_LAW_PID: pid(m, t_s); break;
    case ORC_LAW_CT: computed_torque(m, t_s); break;
    case ORC_MODEL_DYN: dynamic_model(m); break;
    case ORC_CT_FEEDBACK: ct_feedback(m); break;
    case ORC_OBS_JOINT_LIMITS: joint_limits(m); break;
    case ORC_OBS_TORQUE_SAT: torque_saturation(m); break;
    case ORC_OBS_TRACKING: tracking_error(m); break;
    case ORC_OBS_AT_REST: at_rest(m); break;
    case ORC_AUV_AUTOPILOT: autopilot(m, t_s); break;
    case ORC_AUV_GUIDANCE: guidance(m); break;
    case ORC_AUV_OBSERVER: auv_observer(m, t_s); break;
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

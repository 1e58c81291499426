/* orccad_mt.h: the Module-Tasks of ORCCAD in C (RR-1801 §3.2: init; loop { read; compute;
 * write }). Part of the ORCCAD runtime library; C99, no allocation, no recursion.
 *
 * One orc_mt holds one Module-Task instance: its kind, its input and output slots (in the
 * order of the Python kind's ports), its parameters and its state. Everything lives in the
 * struct, owned by the caller (two instances in one process just work).
 *
 * Lifecycle, as the executive drives a Python module instance:
 *   orc_mt_load(m, def)         copy the nominal parameters of the generated table entry
 *   orc_mt_init(m)              at each activation: reset state (integrators, clocks)
 *   orc_mt_compute(m, t_s)      one job: reads m->in[], writes m->out[] (present flags)
 *   orc_mt_set_param(m, o, v, n) a type-1 update: parameters [o, o+n) replaced
 */
#ifndef ORCCAD_MT_H
#define ORCCAD_MT_H

#include <stdint.h>

#define ORC_MAX_DIM 16     /* components of a vector port (M of 4 joints: 16) */
#define ORC_MAX_PORTS 8    /* input (and output) slots of a Module-Task */
#define ORC_MAX_PARAMS 192 /* doubles of parameters */
#define ORC_MAX_STATE 160  /* doubles of state */

/* Module-Task kinds with a C implementation (the Python kind in the comment). */
enum orc_kind {
    ORC_TRAJ_COSINE = 1,       /* trajectory, cosine(q0, omega) */
    ORC_TRAJ_MIN_JERK = 2,     /* trajectory, min_jerk(goal, duration[, start]) */
    ORC_TRAJ_CONSTANT = 3,     /* trajectory, constant([value]) */
    ORC_LAW_PID = 10,          /* control_law, pid with joint_tracking */
    ORC_LAW_CT = 11,           /* control_law, computed_torque (pinocchio or perturbed model) */
    ORC_MODEL_DYN = 12,        /* dynamic_model */
    ORC_CT_FEEDBACK = 13       /* ct_feedback */
};

/* One port value: present (0: "none yet" / not written) and its components. */
typedef struct {
    int present;
    int dim;
    double v[ORC_MAX_DIM];
} orc_value;

/* A generated table entry: the nominal Module-Task (its parameters from the .orc file and
 * the robot file). */
typedef struct {
    const char *name;          /* TCS name, e.g. "TrackPID.ctrl" */
    int kind;                  /* enum orc_kind */
    int n_in, n_out;
    int in_dim[ORC_MAX_PORTS];
    int out_dim[ORC_MAX_PORTS];
    int n_params;
    double params[ORC_MAX_PARAMS];
    int64_t period_ns, wcet_ns; /* declared timing [ns] (sporadic: period = minimum
                                 * inter-arrival); 64 bits on every target */
    int processor, priority;   /* placement (priority 1 the highest) */
    int sporadic;              /* 1: released by the writes on its inputs (interrupts) */
    int event_out;             /* 1: output slot 0 is an event port (an observer's event) */
} orc_mt_def;

typedef struct {
    const orc_mt_def *def;
    int kind;
    int n_in, n_out;
    orc_value in[ORC_MAX_PORTS];
    orc_value out[ORC_MAX_PORTS];
    double p[ORC_MAX_PARAMS];
    double s[ORC_MAX_STATE];
} orc_mt;

void orc_mt_load(orc_mt *m, const orc_mt_def *def);
void orc_mt_init(orc_mt *m);
/* 0 on success; -1 for an unknown kind. */
int orc_mt_compute(orc_mt *m, double t_s);
/* 0 on success; -1 when [offset, offset + n) is outside the parameters. */
int orc_mt_set_param(orc_mt *m, int offset, const double *values, int n);

/* The generated table (one per mission): ORC_MODULES[0 .. ORC_N_MODULES). */
extern const orc_mt_def ORC_MODULES[];
extern const int ORC_N_MODULES;
extern const char ORC_TABLE_DIGEST[];
/* A connection of the TCS (RR-1801 §3.2.1): module -1 is the robot (its port index in
 * ORC_ROBOT_PORTS); protocol: enum orc_protocol of orccad_port.h (0: asyn/asyn). */
typedef struct {
    int src_module, src_slot, dst_module, dst_slot, protocol;
} orc_connection;

/* A robot port a Module-Task reads (a sensor) or writes (an actuator). */
typedef struct {
    const char *name;  /* "arm.q" */
    int dim;
    int actuator;
} orc_robot_port;

extern const orc_connection ORC_CONNECTIONS[];
extern const int ORC_N_CONNECTIONS;
extern const orc_robot_port ORC_ROBOT_PORTS[];
extern const int ORC_N_ROBOT_PORTS;
extern const int ORC_N_PROCESSORS;

/* The generated instances' memory, one per table entry (no allocation at run time). */
extern orc_mt ORC_INSTANCES[];

/* What a kind's C may call (the runtime library's kinds and the plugins' alike). */
/* Output slot `slot` written: present, `dim` components from v. */
void orc_mt_set_out(orc_mt *m, int slot, const double *v, int dim);
void orc_mt_set_out1(orc_mt *m, int slot, double v);
/* ModuleInstance.task_time: seconds since the first job after init; `state` holds
 * [t0 set, t0] (two words of the kind's state). */
double orc_mt_task_time(double *state, double t_s);
/* An observer's job (plugins/orccad_observers/base.py): its value on output slot 1; its
 * event on slot 0 when `holds`, only at the rising edge when the edge parameter p[0] is set
 * (the state's s[0] is "held"). */
void orc_mt_observe(orc_mt *m, int holds, double value);
/* The torque interval [lo, hi] [N·m] the actuator constraint allows joint j at velocity
 * qdot (control/constraints.py: |tau + beta·qdot| <= alpha within [tau_min, tau_max], never
 * empty); bounds = [tau_min, tau_max, alpha, beta], dof each. The laws clamp to it,
 * torque_saturation measures against it. */
void orc_mt_torque_bounds(const double *bounds, int dof, int j, double qdot, double *lo,
                          double *hi);

/* The plugin kinds' C (ModuleKind.c_implementation; docs/deploy.md): kind ORC_PLUGIN_BASE + k
 * is the table's k-th plugin kind, its functions PREFIX_init(orc_mt *) and
 * PREFIX_compute(orc_mt *, double) called through these two, which the generated table
 * defines; -1 for a kind that is not a plugin's. */
#define ORC_PLUGIN_BASE 100
int orc_plugin_init(orc_mt *m);
int orc_plugin_compute(orc_mt *m, double t_s);

#endif

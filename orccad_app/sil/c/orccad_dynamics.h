/* orccad_dynamics.h: M(q) and N(q, qdot) of a chain of revolute joints (orccad_dynamics.c). */
#ifndef ORCCAD_DYNAMICS_H
#define ORCCAD_DYNAMICS_H

#define ORC_MAX_JOINTS 8

/* One joint of the model, as orccad emits it from Pinocchio's model of the robot file. */
typedef struct {
    int parent;          /* index of the parent joint, -1 for the base */
    double axis[3];      /* the revolute axis in the joint frame (unit) */
    double rotation[9];  /* the joint placement in its parent's frame: rotation, row major */
    double translation[3];
    double mass;         /* the body carried by the joint [kg] */
    double lever[3];     /* its centre of mass in the joint frame [m] */
    double inertia[6];   /* its inertia at the centre of mass: xx, xy, xz, yy, yz, zz */
    double armature;     /* added to M's diagonal [kg·m²] */
} orc_joint;

typedef struct {
    int n;
    double gravity[3];   /* [m/s²], (0, 0, -9.81) */
    orc_joint joints[ORC_MAX_JOINTS];
} orc_model;

/* M(q) [kg·m²], n x n row major, symmetric */
void orc_mass_matrix(const orc_model *model, const double *q, double *mass);
/* N(q, qdot) [N·m]: Coriolis, centrifugal and gravity torques (no damping) */
void orc_nonlinear_effects(const orc_model *model, const double *q, const double *qdot,
                           double *out);

#endif

/* orccad_adjust.h: the functions of a type-1 update's computed value in the controller
 * (orccad_app/sil/adjust.py generates the expressions that call them; the automaton task,
 * orccad_rt_automaton.c, evaluates them). numpy's minimum, maximum and clip on two doubles,
 * as the mission layer computes an update (orccad_app/robottask/updates.py): a NaN operand
 * gives NaN, equal operands give the second (0.0 and -0.0), clip with swapped bounds is
 * refused (*ok = 0). Part of the ORCCAD runtime library; C99, no allocation. */
#ifndef ORCCAD_ADJUST_H
#define ORCCAD_ADJUST_H

static inline double adjust_min(double a, double b)
{
    return (a < b || a != a) ? a : b;
}

static inline double adjust_max(double a, double b)
{
    return (a > b || a != a) ? a : b;
}

static inline double adjust_clip(double x, double lo, double hi, int *ok)
{
    if (lo > hi) {
        *ok = 0;
    }
    return adjust_min(adjust_max(x, lo), hi);
}

#endif

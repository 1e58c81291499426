/* low_pass.c: the C of the test plugin kind `low_pass` (tests/sil/test_plugin_c.py), the
 * first-order low-pass filter of docs/plugins.md: y += (1 - exp(-2 pi f_c dt)) (u - y).
 * Parameters: m->p[0] = cutoff [Hz]. State: s[0] 1 once y holds a value, s[1] the previous
 * job's time [s], s[2..] y. */
#include <math.h>

#include "orccad_mt.h"

void low_pass_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state */
}

void low_pass_compute(orc_mt *m, double t_s)
{
    const double pi = 3.141592653589793;
    const double *u = m->in[0].v;
    double *y = &m->s[2];
    int i, dim = m->in[0].dim;
    if (!m->in[0].present) {
        return;
    }
    if (m->s[0] == 0.0) {
        for (i = 0; i < dim; i++) {
            y[i] = u[i];
        }
        m->s[0] = 1.0;
    } else {
        double alpha = 1.0 - exp(-2.0 * pi * m->p[0] * (t_s - m->s[1]));
        for (i = 0; i < dim; i++) {
            y[i] = y[i] + alpha * (u[i] - y[i]);
        }
    }
    m->s[1] = t_s;
    m->out[0].present = 1;
    for (i = 0; i < dim; i++) {
        m->out[0].v[i] = y[i];
    }
}

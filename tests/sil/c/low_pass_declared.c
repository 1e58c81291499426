/* low_pass_declared.c: the test plugin kind `low_pass` with its parameters and state declared
 * once (tests/sil/test_plugin_c.py: CImplementation.param_fields, state_fields): the structs
 * come from the generated low_pass_d_kind.h, no offset is written here. */
#include <math.h>

#include "low_pass_d_kind.h"
#include "orccad_mt.h"

void low_pass_d_init(orc_mt *m)
{
    (void)m; /* the runtime zeroed the state: primed = 0 */
}

void low_pass_d_compute(orc_mt *m, double t_s)
{
    const double pi = 3.141592653589793;
    low_pass_d_params p = low_pass_d_params_of(m);
    low_pass_d_state s = low_pass_d_state_of(m);
    const double *u = m->in[0].v;
    int64_t i, dim = m->in[0].dim;
    if (!m->in[0].present) {
        return;
    }
    if (!s.primed) {
        for (i = 0; i < dim; i++) {
            s.y[i] = u[i];
        }
        s.primed = 1;
    } else {
        double alpha = 1.0 - exp(-2.0 * pi * p.cutoff_hz * (t_s - s.last_t_s));
        for (i = 0; i < dim; i++) {
            s.y[i] = s.y[i] + alpha * (u[i] - s.y[i]);
        }
    }
    s.last_t_s = t_s;
    m->out[0].present = 1;
    for (i = 0; i < dim; i++) {
        m->out[0].v[i] = s.y[i];
    }
    low_pass_d_save_state(m, &s);
}

/* orccad_rt_record.c: the trace's records of the real-time runtime's jobs (orc_io_job of
 * orccad_io.h, while orc_io_jobs_wanted): a job's life cycle (release, compute start and end,
 * finish or abort, deadline miss) and each skipped release, instants from the run's t = 0.
 * Part of the ORCCAD runtime library; called under orc_rt_lock. C99 + POSIX threads; no
 * allocation, no recursion. */
#include <stdint.h>

#include "orccad_io.h"
#include "orccad_rt.h"
#include "orccad_rt_task.h"

void orc_rt_record_job(int m, int64_t finish_ns, int missed)
{
    const rt_task *t = orc_rt_task(m);
    int64_t epoch_ns = orc_rt_epoch_ns();
    orc_job job;
    job.job = t->released - 1;
    job.release_ns = t->job_release_ns - epoch_ns;
    job.start_ns = t->job_start_ns < 0 ? -1 : t->job_start_ns - epoch_ns;
    job.compute_end_ns = t->job_compute_end_ns < 0 ? -1 : t->job_compute_end_ns - epoch_ns;
    job.finish_ns = finish_ns < 0 ? -1 : finish_ns - epoch_ns;
    job.missed = missed;
    job.overrun = 0;
    orc_io_job(m, &job);
}

void orc_rt_record_overrun(int m, int64_t release_ns)
{
    int64_t epoch_ns = orc_rt_epoch_ns();
    orc_job job;
    if (!orc_io_jobs_wanted()) {
        return;
    }
    job.job = orc_rt_task(m)->released - 1;
    job.release_ns = release_ns - epoch_ns;
    job.start_ns = job.compute_end_ns = job.finish_ns = -1;
    job.missed = 0;
    job.overrun = 1;
    orc_io_job(m, &job);
}

/* batch_reader.c - a batch's models read on a thread of their own: while
 * the batch draws input N with one render job, this thread reads input
 * N+1 (parses the file, makes its normals, loads its textures) into a
 * second job, so that reading overlaps drawing.  Each job has its own
 * contexts, since a context serves one thread at a time; at most two
 * models are held, the one drawn and the next.  The inputs come out in
 * list order, so failures are reported in the order of the list. */
#include "batch_reader.h"

#include <stdio.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* The next input of the shard, or NULL after the last. */
static const batch_item *next_item(batch_reader *r)
{
    while (r->next < r->list->count) {
        const batch_item *it = &r->list->items[r->next++];
        if (batch_in_shard(it->input, r->shard)) {
            return it;
        }
    }
    return NULL;
}

/* Read `it` into slot k with job k, and make the job's framebuffer at
 * its first model; the messages of a failure (or a warning) are held in
 * the slot. */
static void read_into(batch_reader *r, int k, const batch_item *it)
{
    batch_read *s = &r->slots[k];
    render_job *job = r->jobs[k];
    *s = (batch_read){ .item = it, .job = job };
    s->wanted = r->want(r->user, it);
    if (!s->wanted) {
        s->fb = r->fbs[k];
        return;
    }
    double t0 = now_ms();
    cli_capture(s->message, sizeof s->message);
    int status = -1;
    if (r->job_argv) {
        status = render_job_configure(job, r->job_argc, r->job_argv);
    }
    if (status < 0) {
        status = render_job_reload(job, it->input);
    }
    if (status < 0 && !r->fbs[k]) {
        sr_context *ctx = render_job_context(job);
        sr_result res = sr_make_framebuffer(
            ctx, &(sr_framebuffer_desc){ .width = r->width, .height = r->height,
                                         .depth_format = render_job_depth_format(job) },
            &r->fbs[k]);
        if (res != SR_OK) {
            cli_error("%s", sr_context_error(ctx)[0] ? sr_context_error(ctx)
                                                     : sr_result_text(res));
            status = EXIT_FAILURE_RUN;
        }
    }
    cli_capture(NULL, 0);
    s->fb = r->fbs[k];
    s->load_ms = now_ms() - t0;
    s->loaded = status < 0;
}

/* Input k goes into slot k % 2 once input k - 2, which held that slot,
 * has been given back (the batch took input k - 1): filled <= taken. */
static void *reader_main(void *arg)
{
    batch_reader *r = arg;
    pthread_mutex_lock(&r->lock);
    for (;;) {
        while (!r->stop && r->filled > r->taken) {
            pthread_cond_wait(&r->wake, &r->lock);
        }
        if (r->stop) {
            break;
        }
        int k = (int)(r->filled % 2);
        pthread_mutex_unlock(&r->lock);
        const batch_item *it = next_item(r);
        if (it) {
            read_into(r, k, it);
        }
        pthread_mutex_lock(&r->lock);
        r->filled += it != NULL;
        r->end = it == NULL;
        pthread_cond_broadcast(&r->wake);
        if (r->end) {
            break;
        }
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

void batch_reader_start(batch_reader *r, const batch_list *list, const batch_shard *shard,
                        batch_want_fn want, void *user, render_job *jobs[2], int job_argc,
                        char **job_argv, int width, int height)
{
    *r = (batch_reader){ .list = list, .shard = shard, .want = want, .user = user,
                         .job_argv = job_argv, .job_argc = job_argc, .width = width,
                         .height = height, .jobs = { jobs[0], jobs[1] } };
    pthread_mutex_init(&r->lock, NULL);
    pthread_cond_init(&r->wake, NULL);
    r->threaded = pthread_create(&r->thread, NULL, reader_main, r) == 0;
}

batch_read *batch_reader_next(batch_reader *r)
{
    if (!r->threaded) {   /* read it now */
        const batch_item *it = next_item(r);
        int k = (int)(r->taken % 2);
        if (!it) {
            return NULL;
        }
        read_into(r, k, it);
        r->taken++;
        return &r->slots[k];
    }
    pthread_mutex_lock(&r->lock);
    while (r->filled <= r->taken && !r->end) {
        pthread_cond_wait(&r->wake, &r->lock);
    }
    batch_read *s = NULL;
    if (r->filled > r->taken) {
        s = &r->slots[r->taken % 2];
        r->taken++;
        pthread_cond_broadcast(&r->wake);
    }
    pthread_mutex_unlock(&r->lock);
    return s;
}

void batch_reader_stop(batch_reader *r)
{
    if (r->threaded) {
        pthread_mutex_lock(&r->lock);
        r->stop = true;
        pthread_cond_broadcast(&r->wake);
        pthread_mutex_unlock(&r->lock);
        pthread_join(r->thread, NULL);
    }
    pthread_cond_destroy(&r->wake);
    pthread_mutex_destroy(&r->lock);
    for (int k = 0; k < 2; k++) {
        if (r->fbs[k]) {
            sr_destroy_framebuffer(render_job_context(r->jobs[k]), r->fbs[k]);
            r->fbs[k] = NULL;
        }
    }
}

/* batch_reader.h - a batch's models read on a thread of their own
 * (batch_reader.c), one ahead of the one being drawn. */
#ifndef SR_BATCH_READER_H
#define SR_BATCH_READER_H

#include "batch.h"
#include "render.h"

#include <pthread.h>

/* Whether an input is to be read: false when every output it has exists
 * already (--skip-existing).  Called on the reader's thread. */
typedef bool (*batch_want_fn)(void *user, const batch_item *it);

/* One input of the shard, read (or not) into one of the two jobs. */
typedef struct batch_read {
    const batch_item *item;
    render_job *job;           /* holds the model while loaded */
    sr_framebuffer *fb;        /* the job's, made at its first model; NULL until then */
    bool wanted;               /* false: not read (batch_want_fn) */
    bool loaded;               /* read and ready to draw */
    double load_ms;
    char message[2048];        /* why it failed, or a warning when it loaded */
} batch_read;

typedef struct batch_reader {
    const batch_list *list;
    const batch_shard *shard;
    batch_want_fn want;
    void *user;
    char **job_argv;           /* non-NULL: the options each input starts from */
    int job_argc;
    int width, height;         /* the framebuffers' size */
    batch_read slots[2];       /* input k in slots[k % 2], with jobs[k % 2] */
    render_job *jobs[2];
    sr_framebuffer *fbs[2];
    size_t next;               /* the reader's place in the list */
    size_t filled, taken;      /* inputs read, and handed to the batch */
    bool threaded, stop, end;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
} batch_reader;

/* Read the shard's inputs of `list` in order into jobs[0] and jobs[1]
 * (parsed with the same options; jobs[1] shares jobs[0]'s light), on a
 * thread of its own when one can be started.  job_argv, when not NULL,
 * re-reads the options before each input (a turntable turned the last
 * one's camera). */
void batch_reader_start(batch_reader *r, const batch_list *list, const batch_shard *shard,
                        batch_want_fn want, void *user, render_job *jobs[2], int job_argc,
                        char **job_argv, int width, int height);
/* The next input (waiting until it is read), in list order; NULL after
 * the last.  The input before it is given back: its job and framebuffer
 * then read the input after it. */
batch_read *batch_reader_next(batch_reader *r);
/* End the thread and destroy the framebuffers (not the jobs). */
void batch_reader_stop(batch_reader *r);

#endif

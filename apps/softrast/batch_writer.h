/* batch_writer.h - a batch's outputs written on threads of their own
 * (batch_writer.c), overlapping the reading and drawing of the next
 * input. */
#ifndef SR_BATCH_WRITER_H
#define SR_BATCH_WRITER_H

#include "batch.h"
#include "cli.h"

#include <pthread.h>

/* Called on a writer thread once an image is written (or failed:
 * message says why), with its record's status and encode_ms set.  Calls
 * never overlap and come in the order the images were handed over; the
 * batch waits for the writer (batch_writer_wait) before it reports an
 * input itself. */
typedef void (*batch_done_fn)(void *user, batch_record *rec, const char *message);

/* The most writer threads, and the images in hand: each thread's, and one
 * waiting, so that a slow fsync does not stop the drawing at once. */
enum { BATCH_WRITER_MAX_THREADS = 8, BATCH_WRITER_DEPTH = BATCH_WRITER_MAX_THREADS + 1 };
/* More images than one wait only while the copies they hold stay below
 * this many bytes (a batch of large images holds one or two). */
#define BATCH_WRITER_MAX_BYTES ((size_t)256 << 20)

/* An image in hand: its record and its own copy of the pixels. */
typedef struct batch_image {
    batch_record rec;
    char output[4096];         /* rec.output's copy: the batch names the next one */
    uint8_t *pixels;
    size_t capacity, bytes;
    int width, height;
    cli_image_options opt;
    bool written;              /* written, not yet reported */
    const char *message;       /* why it failed, or NULL */
    sr_io_error err;
} batch_image;

typedef struct batch_writer {
    batch_done_fn done;
    void *user;
    pthread_t threads[BATCH_WRITER_MAX_THREADS];
    int thread_count;          /* started; 0: batch_writer_put writes at once */
    int depth;                 /* images in hand at most */
    pthread_mutex_t lock;
    pthread_cond_t wake;
    bool stop, reporting;
    batch_image images[BATCH_WRITER_DEPTH];
    int first, count;          /* the images in hand, oldest first, in a ring */
    int claimed;               /* of those, the first `claimed` are taken by a thread */
    size_t held;               /* bytes of pixels in hand */
} batch_writer;

/* Start `threads` writer threads (1 to BATCH_WRITER_MAX_THREADS): several
 * write (and fsync) images side by side, for batches whose drawing is
 * quicker than the disk.  Without any, batch_writer_put writes at once. */
void batch_writer_start(batch_writer *w, int threads, batch_done_fn done, void *user);
/* Hand over an image (copied): waits while the writer holds as many as
 * it takes.  false when out of memory (nothing handed over). */
bool batch_writer_put(batch_writer *w, const batch_record *rec, int width, int height,
                      const uint8_t *rgba, const cli_image_options *opt);
/* Wait until every image in hand is written and reported. */
void batch_writer_wait(batch_writer *w);
/* Write the last images and end the threads. */
void batch_writer_stop(batch_writer *w);

#endif

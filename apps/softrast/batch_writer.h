/* batch_writer.h - a batch's outputs written on a thread of their own
 * (batch_writer.c), overlapping the reading and drawing of the next
 * model. */
#ifndef SR_BATCH_WRITER_H
#define SR_BATCH_WRITER_H

#include "batch.h"
#include "cli.h"

#include <pthread.h>

/* Called on the writer's thread once an image is written (or failed:
 * message says why), with its record's status and encode_ms set.  The
 * batch waits for the writer (batch_writer_wait) before it reports an
 * input itself, so that calls never overlap and come in list order. */
typedef void (*batch_done_fn)(void *user, batch_record *rec, const char *message);

/* How many images the writer holds: one being written and one waiting,
 * so that a slow fsync does not stop the drawing at once. */
enum { BATCH_WRITER_DEPTH = 2 };

/* An image in hand: its record and its own copy of the pixels. */
typedef struct batch_image {
    batch_record rec;
    char output[4096];         /* rec.output's copy: the batch names the next one */
    uint8_t *pixels;
    size_t capacity;
    int width, height;
    cli_image_options opt;
} batch_image;

typedef struct batch_writer {
    batch_done_fn done;
    void *user;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    bool threaded, stop;
    batch_image images[BATCH_WRITER_DEPTH];
    int first, count;          /* the images in hand, oldest first, in a ring */
} batch_writer;

/* Start the thread (without one, batch_writer_put writes at once). */
void batch_writer_start(batch_writer *w, batch_done_fn done, void *user);
/* Hand over an image (copied): waits while the writer holds
 * BATCH_WRITER_DEPTH already.  false when out of memory (nothing handed
 * over). */
bool batch_writer_put(batch_writer *w, const batch_record *rec, int width, int height,
                      const uint8_t *rgba, const cli_image_options *opt);
/* Wait until every image in hand is written. */
void batch_writer_wait(batch_writer *w);
/* Write the last image and end the thread. */
void batch_writer_stop(batch_writer *w);

#endif

/* batch_writer.c - a batch's image files, written on a thread of their
 * own: while it compresses one image and waits for the disk to take it
 * (each output is fsync'd before it is renamed into place), the batch
 * draws the next model.  It holds up to BATCH_WRITER_DEPTH images, each
 * its own copy of the pixels, so the framebuffer can be drawn again at
 * once and one slow fsync does not stop the drawing; they are written,
 * and reported, in the order they came.  It compresses on one thread: the render job's context
 * is busy drawing. */
#include "batch_writer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

/* Write an image in hand and pass its record on. */
static void write_image(batch_writer *w, batch_image *im)
{
    sr_io_error err = { { 0 } };
    double t0 = now_ms();
    bool ok = cli_make_parents(im->rec.output, &err) &&
              cli_write_image(im->rec.output, im->width, im->height, im->pixels, &im->opt,
                              &err) == SR_OK;
    im->rec.encode_ms = now_ms() - t0;
    im->rec.status = ok ? "ok" : "failed";
    w->done(w->user, &im->rec, ok ? NULL : err.message);
}

/* The oldest image is written while the batch may add the next one to
 * the ring (never into the slot being written: count stays until then). */
static void *writer_main(void *arg)
{
    batch_writer *w = arg;
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (w->count == 0 && !w->stop) {
            pthread_cond_wait(&w->wake, &w->lock);
        }
        if (w->count == 0) {
            break;
        }
        batch_image *im = &w->images[w->first];
        pthread_mutex_unlock(&w->lock);
        write_image(w, im);
        pthread_mutex_lock(&w->lock);
        w->first = (w->first + 1) % BATCH_WRITER_DEPTH;
        w->count--;
        pthread_cond_broadcast(&w->wake);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

void batch_writer_start(batch_writer *w, batch_done_fn done, void *user)
{
    *w = (batch_writer){ .done = done, .user = user };
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->wake, NULL);
    w->threaded = pthread_create(&w->thread, NULL, writer_main, w) == 0;
}

/* Wait until the writer holds at most `most` images. */
static void wait_for(batch_writer *w, int most)
{
    pthread_mutex_lock(&w->lock);
    while (w->count > most) {
        pthread_cond_wait(&w->wake, &w->lock);
    }
    pthread_mutex_unlock(&w->lock);
}

void batch_writer_wait(batch_writer *w)
{
    wait_for(w, 0);
}

bool batch_writer_put(batch_writer *w, const batch_record *rec, int width, int height,
                      const uint8_t *rgba, const cli_image_options *opt)
{
    wait_for(w, BATCH_WRITER_DEPTH - 1);
    /* Only this thread adds images, so the free slot stays free. */
    pthread_mutex_lock(&w->lock);
    batch_image *im = &w->images[(w->first + w->count) % BATCH_WRITER_DEPTH];
    pthread_mutex_unlock(&w->lock);
    size_t bytes = 4 * (size_t)width * (size_t)height;
    if (bytes > im->capacity) {
        uint8_t *grown = realloc(im->pixels, bytes);
        if (!grown) {
            return false;
        }
        im->pixels = grown;
        im->capacity = bytes;
    }
    memcpy(im->pixels, rgba, bytes);
    im->rec = *rec;
    snprintf(im->output, sizeof im->output, "%s", rec->output);
    im->rec.output = im->output;
    im->width = width;
    im->height = height;
    im->opt = *opt;
    im->opt.context = NULL;   /* the render job's context is not ours to use */
    im->opt.inputs = NULL;    /* the batch checked them; the job's change with the next model */
    if (!w->threaded) {
        write_image(w, im);
        return true;
    }
    pthread_mutex_lock(&w->lock);
    w->count++;
    pthread_cond_broadcast(&w->wake);
    pthread_mutex_unlock(&w->lock);
    return true;
}

void batch_writer_stop(batch_writer *w)
{
    if (w->threaded) {
        pthread_mutex_lock(&w->lock);
        w->stop = true;
        pthread_cond_broadcast(&w->wake);
        pthread_mutex_unlock(&w->lock);
        pthread_join(w->thread, NULL);
    }
    pthread_cond_destroy(&w->wake);
    pthread_mutex_destroy(&w->lock);
    for (int i = 0; i < BATCH_WRITER_DEPTH; i++) {
        free(w->images[i].pixels);
        w->images[i].pixels = NULL;
    }
}

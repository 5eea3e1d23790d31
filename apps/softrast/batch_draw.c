/* batch_draw.c - a batch's inputs drawn on several threads at once and
 * handed on in the order of the list (batch_session_each).  The drawing
 * threads take the shard's inputs in list order, each into the next of a
 * ring of slots; each checks its input (--skip-existing, an output over
 * an input) and draws it with the slot's own things.  The batch's thread
 * takes the slots back in the same order: it reports the input, hands
 * the picture to the writer, which copies it, and frees the slot.  So the
 * log, the messages and the progress come as if one thread drew them
 * all, whichever drawing ends first; at most one drawing a slot is in
 * hand, and the finished ones wait only while their pixels stay below
 * BATCH_DRAW_MAX_BYTES. */
#include "batch_session.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef enum slot_state { SLOT_FREE, SLOT_DRAWING, SLOT_DONE } slot_state;

typedef struct draw_slot {
    slot_state state;
    bool ok, skipped;
    size_t bytes;              /* the picture's, while it waits */
    batch_record rec;
    batch_picture pic;
    char message[2048];        /* why it failed, or its warnings */
} draw_slot;

typedef struct draw_run {
    batch_session *s;
    const batch_drawer *d;
    draw_slot *slots;
    int slot_count;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    size_t next;               /* the list's next input of the shard not taken */
    size_t taken, handed;      /* inputs taken by a drawing thread, and handed on */
    size_t held;               /* bytes of the pictures drawn, not yet handed on */
} draw_run;

int batch_draw_slots(int threads)
{
    /* One waiting behind each one drawing: a slow drawing does not stop
     * the others at once. */
    threads = threads < 1 ? 1 : threads > BATCH_DRAW_MAX_THREADS ? BATCH_DRAW_MAX_THREADS
                                                                  : threads;
    return 2 * threads;
}

/* Move r->next to the shard's next input (the list's count at the end). */
static void skip_others(draw_run *r)
{
    const batch_list *l = &r->s->list;
    while (r->next < l->count && !batch_in_shard(l->items[r->next].input, &r->s->shard)) {
        r->next++;
    }
}

/* Whether an input is left and may be taken now: a slot is free, and the
 * pictures waiting leave room (none wait when none are taken, so the
 * batch's thread always has one to wait for). */
static bool can_take(const draw_run *r)
{
    return r->next < r->s->list.count && r->taken - r->handed < (size_t)r->slot_count &&
           r->held <= BATCH_DRAW_MAX_BYTES;
}

/* Take the next input into its slot; called and returns with the lock
 * held. */
static draw_slot *take(draw_run *r, size_t *item, int *slot)
{
    *slot = (int)(r->taken++ % (size_t)r->slot_count);
    *item = r->next++;
    skip_others(r);
    draw_slot *sl = &r->slots[*slot];
    sl->state = SLOT_DRAWING;
    return sl;
}

/* Check and draw one input into its slot, outside the lock. */
static void draw_item(draw_run *r, draw_slot *sl, int slot, size_t item)
{
    batch_session *s = r->s;
    const batch_item *it = &s->list.items[item];
    sl->rec = (batch_record){ .input = it->input, .output = it->output, .index = it->index,
                              .status = "failed" };
    sl->pic = (batch_picture){ 0 };
    sl->message[0] = '\0';
    sl->bytes = 0;
    sl->ok = false;
    sl->skipped = s->opts->skip_existing && batch_exists_whole(it->output);
    if (sl->skipped) {
        sl->rec.status = "skipped";
        return;
    }
    cli_capture(sl->message, sizeof sl->message);   /* this thread's messages */
    const char *namer = it->named ? "--batch output" : "--name";
    /* A list's OUTPUT (or a name ending in {ext}) is known only now. */
    bool ok = cli_check_image_name(namer, it->output, true) &&
              batch_session_output_ok(s, it->output, namer);
    cli_capture(NULL, 0);
    sl->ok = ok && r->d->draw(r->d->user, slot, it, &sl->pic, &sl->rec, sl->message,
                              sizeof sl->message);
    if (sl->ok) {
        sl->bytes = 4 * (size_t)sl->pic.width * (size_t)sl->pic.height;
    }
}

/* Mark a slot drawn; with the lock held. */
static void drawn(draw_run *r, draw_slot *sl)
{
    sl->state = SLOT_DONE;
    r->held += sl->bytes;
    pthread_cond_broadcast(&r->wake);
}

static void *drawer_main(void *arg)
{
    draw_run *r = arg;
    pthread_mutex_lock(&r->lock);
    for (;;) {
        while (r->next < r->s->list.count && !can_take(r)) {
            pthread_cond_wait(&r->wake, &r->lock);
        }
        if (r->next >= r->s->list.count) {
            break;
        }
        size_t item;
        int slot;
        draw_slot *sl = take(r, &item, &slot);
        pthread_mutex_unlock(&r->lock);
        draw_item(r, sl, slot, item);
        pthread_mutex_lock(&r->lock);
        drawn(r, sl);
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

/* Report an input that is not handed to the writer, after those that
 * were (records come in list order). */
static void done_here(batch_session *s, batch_record *rec, const char *message)
{
    batch_writer_wait(&s->writer);
    batch_session_done(s, rec, message);
}

/* Report a drawn slot and hand its picture to the writer, on the batch's
 * thread. */
static void hand_on(batch_session *s, draw_slot *sl)
{
    if (sl->skipped) {
        done_here(s, &sl->rec, NULL);
        return;
    }
    bool ok = sl->ok;
    if (ok && sl->message[0]) {
        batch_writer_wait(&s->writer);
        batch_session_report(s, sl->rec.input, sl->message);   /* warnings */
    }
    if (ok && !batch_writer_put(&s->writer, &sl->rec, sl->pic.width, sl->pic.height,
                                sl->pic.rgba, &sl->pic.image)) {
        snprintf(sl->message, sizeof sl->message, "out of memory");
        ok = false;
    }
    if (!ok) {
        done_here(s, &sl->rec, sl->message);
    }
}

void batch_session_each(batch_session *s, const batch_drawer *d)
{
    draw_run r = { .s = s, .d = d, .slot_count = batch_draw_slots(d->threads) };
    int threads = r.slot_count / 2;
    size_t mine = batch_session_mine(s);
    if ((size_t)threads > mine) {
        threads = (int)mine;   /* no thread without an input */
    }
    draw_slot alone = { 0 };
    r.slots = calloc((size_t)r.slot_count, sizeof *r.slots);
    if (!r.slots) {
        r.slots = &alone;   /* one at a time on this thread */
        r.slot_count = 1;
        threads = 0;
    }
    pthread_mutex_init(&r.lock, NULL);
    pthread_cond_init(&r.wake, NULL);
    skip_others(&r);
    pthread_t ids[BATCH_DRAW_MAX_THREADS];
    int started = 0;
    pthread_mutex_lock(&r.lock);
    while (started < threads && pthread_create(&ids[started], NULL, drawer_main, &r) == 0) {
        started++;
    }
    for (;;) {
        draw_slot *head = &r.slots[r.handed % (size_t)r.slot_count];
        if (r.handed == r.taken && r.next >= s->list.count) {
            break;
        }
        if (started == 0 && r.handed == r.taken) {
            /* No thread could be started: draw here, one at a time. */
            size_t item;
            int slot;
            draw_slot *sl = take(&r, &item, &slot);
            pthread_mutex_unlock(&r.lock);
            draw_item(&r, sl, slot, item);
            pthread_mutex_lock(&r.lock);
            drawn(&r, sl);
        }
        if (r.handed == r.taken || head->state != SLOT_DONE) {
            pthread_cond_wait(&r.wake, &r.lock);
            continue;
        }
        int slot = (int)(r.handed % (size_t)r.slot_count);
        pthread_mutex_unlock(&r.lock);
        hand_on(s, head);
        if (d->release) {
            d->release(d->user, slot);
        }
        pthread_mutex_lock(&r.lock);
        r.held -= head->bytes;
        head->state = SLOT_FREE;
        r.handed++;
        pthread_cond_broadcast(&r.wake);
    }
    pthread_mutex_unlock(&r.lock);
    for (int i = 0; i < started; i++) {
        pthread_join(ids[i], NULL);
    }
    pthread_cond_destroy(&r.wake);
    pthread_mutex_destroy(&r.lock);
    if (r.slots != &alone) {
        free(r.slots);
    }
    batch_writer_wait(&s->writer);
}

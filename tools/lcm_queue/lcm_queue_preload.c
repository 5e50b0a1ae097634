// libugv-lcm-queue.so: an LD_PRELOAD for lcm-logger (LCM 1.3.1) that raises the queue
// capacity of every subscription it makes.
//
// liblcm's receive thread queues each message for lcm_handle(); a subscription holds at most
// 30 (liblcm's default), and a message beyond that is dropped without a word (it is the
// newest that goes). lcm-logger never changes the default. So whenever its main loop is not
// scheduled while more than 30 messages arrive, as after any stall of the machine, it loses
// the rest: stopped (SIGSTOP) while 300 small messages were published, it kept 31 of them.
// Our own daemons do not receive through liblcm's queue (lib/bus UdpmReceiver).
//
// lcm-logger has its own bound behind this one: at most 100 MB of unwritten messages
// (--max-unwritten-mb), after which it drops and says so. UGV_LCM_QUEUE_CAPACITY sets the
// number of messages (default 100000, 0 = no limit).
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#include <lcm/lcm.h>

typedef lcm_subscription_t* (*subscribe_fn)(lcm_t*, const char*, lcm_msg_handler_t, void*);

static int queue_capacity(void)
{
    const char* s = getenv("UGV_LCM_QUEUE_CAPACITY");
    if (s == NULL || *s == '\0') return 100000;
    char* end = NULL;
    const long v = strtol(s, &end, 10);
    if (*end != '\0' || v < 0 || v > 100000000) {
        fprintf(stderr, "libugv-lcm-queue: UGV_LCM_QUEUE_CAPACITY=%s is not a count of 0..100000000; using 100000\n", s);
        return 100000;
    }
    return (int) v;
}

lcm_subscription_t* lcm_subscribe(lcm_t* lcm, const char* channel, lcm_msg_handler_t handler, void* userdata)
{
    subscribe_fn real = (subscribe_fn) dlsym(RTLD_NEXT, "lcm_subscribe");
    if (real == NULL) {
        fprintf(stderr, "libugv-lcm-queue: lcm_subscribe not found after the preload: %s\n", dlerror());
        return NULL;
    }
    lcm_subscription_t* sub = real(lcm, channel, handler, userdata);
    if (sub != NULL) lcm_subscription_set_queue_capacity(sub, queue_capacity());
    return sub;
}

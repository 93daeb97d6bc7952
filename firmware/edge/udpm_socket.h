/*
 * The receive socket of an LCM udpm provider, for the host node: its kernel buffer sized, and the
 * datagrams the kernel dropped on it counted. Host code (Linux).
 *
 * Why the node reaches past LCM's API (LCM 1.3.1, lcm/lcm_udpm.c): a receive thread reads every
 * datagram as soon as it arrives into LCM's own ring buffer (200 KiB, grown by half whenever it is
 * full: LCM itself never drops a message, it takes memory), and lcm_handle() hands the queued messages
 * out one per call. So frames are lost only in the kernel, when that thread is not scheduled for
 * longer than the socket's buffer lasts (a busy machine), and LCM shows no count of them. Its URL
 * option recv_buf_size sets SO_RCVBUF, which the kernel caps at net.core.rmem_max; a process with
 * CAP_NET_ADMIN (root) may go past the cap with SO_RCVBUFFORCE, which LCM does not use. The kernel
 * counts the datagrams it dropped on the socket (SO_MEMINFO's SK_MEMINFO_DROPS).
 */
#ifndef TVO_UDPM_SOCKET_H
#define TVO_UDPM_SOCKET_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** UDP sockets bound to the port before LCM made its own (inherited from a parent: a plant that
 *  started the node shares its port), which tvo_udpm_socket_open must pass over. */
#define TVO_UDPM_SOCKET_CENSUS_MAX 16

typedef struct {
    int count;
    int fd[TVO_UDPM_SOCKET_CENSUS_MAX];
} tvo_udpm_socket_census_t;

typedef struct {
    int fd;                      /* LCM's receive socket, or -1 (not udpm, or not found) */
    int port;                    /* the udpm URL's port */
    int forced;                  /* the size was set past net.core.rmem_max (SO_RCVBUFFORCE) */
    uint32_t buffer_bytes;       /* the kernel's receive buffer as it reports it (SO_RCVBUF: twice the request) */
    uint32_t drops_at_start;     /* the kernel's drop count when the socket was found */
} tvo_udpm_socket_t;

/**
 * The udpm port of an LCM URL (NULL: $LCM_DEFAULT_URL, else LCM's default), or -1 if the URL is no
 * udpm URL; *has_recv_buf_size says whether it sets LCM's recv_buf_size option.
 */
int tvo_udpm_url_port(const char *url, int *has_recv_buf_size);

/** The UDP sockets this process has bound to `port` now: call it before lcm_create. */
void tvo_udpm_socket_census(tvo_udpm_socket_census_t *census, int port);

/**
 * Finds this process's UDP socket bound to `port` that the census (NULL: none) did not list: LCM's
 * receive socket (call after lcm_subscribe), and, if request_bytes > 0, asks for that receive buffer:
 * SO_RCVBUFFORCE when the process may, else SO_RCVBUF (capped by the kernel). 0, or -1 if no such
 * socket was found (sock->fd -1).
 */
int tvo_udpm_socket_open(tvo_udpm_socket_t *sock, int port, uint32_t request_bytes,
                         const tvo_udpm_socket_census_t *before);

/** Datagrams the kernel dropped on the socket since tvo_udpm_socket_open (0 if none was found). */
uint32_t tvo_udpm_socket_drops(const tvo_udpm_socket_t *sock);

#ifdef __cplusplus
}
#endif

#endif /* TVO_UDPM_SOCKET_H */

/* LCM's udpm receive socket: its buffer and its kernel drop count (Linux); see udpm_socket.h. */
#define _GNU_SOURCE /* SO_RCVBUFFORCE, SO_MEMINFO */

#include "udpm_socket.h"

#include <linux/sock_diag.h>
#include <netinet/in.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

/* LCM 1.3.1's own default (lcm/lcm.c), used when neither a URL nor $LCM_DEFAULT_URL is given. */
#define LCM_DEFAULT_URL_1_3 "udpm://239.255.76.67:7667?ttl=0"
/* File descriptors looked at for the socket: LCM opens its sockets among a process's first few. */
#define FD_SCAN_LIMIT 1024

int tvo_udpm_url_port(const char *url, int *has_recv_buf_size)
{
    if (has_recv_buf_size != NULL) {
        *has_recv_buf_size = 0;
    }
    if (url == NULL) {
        url = getenv("LCM_DEFAULT_URL");
    }
    if (url == NULL || url[0] == '\0') {
        url = LCM_DEFAULT_URL_1_3;
    }
    if (strncmp(url, "udpm://", 7) != 0) {
        return -1;
    }
    const char *options = strchr(url, '?');
    if (has_recv_buf_size != NULL && options != NULL) {
        *has_recv_buf_size = strstr(options, "recv_buf_size=") != NULL;
    }
    /* udpm://ADDRESS:PORT?...; LCM's own default port when the URL names none. */
    const char *host = url + 7;
    const char *colon = strchr(host, ':');
    if (colon == NULL || (options != NULL && colon > options)) {
        return 7667;
    }
    char *end = NULL;
    const long port = strtol(colon + 1, &end, 10);
    return (end != colon + 1 && port > 0 && port <= 65535) ? (int)port : -1;
}

static uint32_t kernel_drops(int fd)
{
    uint32_t meminfo[SK_MEMINFO_VARS];
    socklen_t size = sizeof(meminfo);
    memset(meminfo, 0, sizeof(meminfo));
    if (fd < 0 || getsockopt(fd, SOL_SOCKET, SO_MEMINFO, meminfo, &size) != 0 || size <= SK_MEMINFO_DROPS * sizeof(uint32_t)) {
        return 0u;
    }
    return meminfo[SK_MEMINFO_DROPS];
}

/* 1 if fd is a UDP (IPv4) socket bound to port. */
static int bound_to(int fd, int port)
{
    int type = 0;
    socklen_t type_size = sizeof(type);
    struct sockaddr_in address;
    socklen_t address_size = sizeof(address);
    return getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &type_size) == 0 && type == SOCK_DGRAM &&
           getsockname(fd, (struct sockaddr *)&address, &address_size) == 0 && address.sin_family == AF_INET &&
           ntohs(address.sin_port) == port;
}

void tvo_udpm_socket_census(tvo_udpm_socket_census_t *census, int port)
{
    if (census == NULL) {
        return;
    }
    census->count = 0;
    for (int fd = 0; port > 0 && fd < FD_SCAN_LIMIT && census->count < TVO_UDPM_SOCKET_CENSUS_MAX; ++fd) {
        if (bound_to(fd, port)) {
            census->fd[census->count++] = fd;
        }
    }
}

static int listed(const tvo_udpm_socket_census_t *census, int fd)
{
    for (int i = 0; census != NULL && i < census->count && i < TVO_UDPM_SOCKET_CENSUS_MAX; ++i) {
        if (census->fd[i] == fd) {
            return 1;
        }
    }
    return 0;
}

int tvo_udpm_socket_open(tvo_udpm_socket_t *sock, int port, uint32_t request_bytes,
                         const tvo_udpm_socket_census_t *before)
{
    if (sock == NULL) {
        return -1;
    }
    memset(sock, 0, sizeof(*sock));
    sock->fd = -1;
    sock->port = port;
    if (port <= 0) {
        return -1;
    }
    for (int fd = 0; fd < FD_SCAN_LIMIT && sock->fd < 0; ++fd) {
        if (bound_to(fd, port) && !listed(before, fd)) {
            sock->fd = fd;
        }
    }
    if (sock->fd < 0) {
        return -1;
    }
    if (request_bytes > 0u && request_bytes <= (uint32_t)INT32_MAX) {
        const int request = (int)request_bytes;
        sock->forced = setsockopt(sock->fd, SOL_SOCKET, SO_RCVBUFFORCE, &request, sizeof(request)) == 0;
        if (!sock->forced) {
            (void)setsockopt(sock->fd, SOL_SOCKET, SO_RCVBUF, &request, sizeof(request));
        }
    }
    int actual = 0;
    socklen_t actual_size = sizeof(actual);
    if (getsockopt(sock->fd, SOL_SOCKET, SO_RCVBUF, &actual, &actual_size) == 0 && actual > 0) {
        sock->buffer_bytes = (uint32_t)actual;
    }
    sock->drops_at_start = kernel_drops(sock->fd);
    return 0;
}

uint32_t tvo_udpm_socket_drops(const tvo_udpm_socket_t *sock)
{
    if (sock == NULL || sock->fd < 0) {
        return 0u;
    }
    return kernel_drops(sock->fd) - sock->drops_at_start;
}

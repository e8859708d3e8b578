/* SocketCAN raw sockets (see socketcan.h). */
#include "co_lx/socketcan.h"

#include <errno.h>
#include <fcntl.h>
#include <net/if.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <linux/can/error.h>
#include <linux/can/raw.h>

#ifndef ARPHRD_CAN
#define ARPHRD_CAN 280
#endif

static int fail(int fd, co_lx_can_fail_t *why, co_lx_can_fail_t what)
{
    int e = errno;

    if (fd >= 0) {
        (void)close(fd);
    }
    if (why != NULL) {
        *why = what;
    }
    errno = e;
    return -1;
}

int co_lx_can_open(const char *iface, co_lx_can_fail_t *why)
{
    struct sockaddr_can addr;
    struct ifreq ifr;
    can_err_mask_t errmask = CAN_ERR_CRTL | CAN_ERR_BUSOFF | CAN_ERR_RESTARTED;
    int on = 1;
    int fd;

    if (why != NULL) {
        *why = CO_LX_CAN_OK;
    }
    if ((strlen(iface) == 0U) || (strlen(iface) >= sizeof ifr.ifr_name)) {
        errno = ENODEV;
        return fail(-1, why, CO_LX_CAN_NO_IFACE);
    }
    fd = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) {
        return fail(-1, why,
                    ((errno == EAFNOSUPPORT) || (errno == EPROTONOSUPPORT) || (errno == EINVAL))
                        ? CO_LX_CAN_NO_SUPPORT : CO_LX_CAN_OTHER);
    }
    (void)memset(&ifr, 0, sizeof ifr);
    (void)memcpy(ifr.ifr_name, iface, strlen(iface));
    if (ioctl(fd, SIOCGIFINDEX, &ifr) < 0) {
        return fail(fd, why, (errno == ENODEV) ? CO_LX_CAN_NO_IFACE : CO_LX_CAN_OTHER);
    }
    (void)memset(&addr, 0, sizeof addr);
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (ioctl(fd, SIOCGIFHWADDR, &ifr) == 0) {
        if (ifr.ifr_hwaddr.sa_family != ARPHRD_CAN) {
            errno = EINVAL;
            return fail(fd, why, CO_LX_CAN_NOT_CAN);
        }
    }
    if ((ioctl(fd, SIOCGIFFLAGS, &ifr) == 0) && ((ifr.ifr_flags & IFF_UP) == 0)) {
        errno = ENETDOWN;
        return fail(fd, why, CO_LX_CAN_DOWN);
    }
    if (setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &errmask, (socklen_t)sizeof errmask) < 0) {
        return fail(fd, why, CO_LX_CAN_OTHER);
    }
    (void)setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &on, (socklen_t)sizeof on);
    if (bind(fd, (struct sockaddr *)&addr, (socklen_t)sizeof addr) < 0) {
        return fail(fd, why, (errno == ENETDOWN) ? CO_LX_CAN_DOWN : CO_LX_CAN_OTHER);
    }
    return fd;
}

void co_lx_frame_to_can(const co_frame_t *f, struct can_frame *cf)
{
    (void)memset(cf, 0, sizeof *cf);
    if ((f->id & CO_FRAME_EFF) != 0U) {
        cf->can_id = (f->id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    } else {
        cf->can_id = f->id & CAN_SFF_MASK;
    }
    if ((f->id & CO_FRAME_RTR) != 0U) {
        cf->can_id |= CAN_RTR_FLAG;
    }
    cf->len = (f->dlc > 8U) ? 8U : f->dlc;
    (void)memcpy(cf->data, f->data, 8U);
}

void co_lx_frame_from_can(const struct can_frame *cf, co_frame_t *f)
{
    uint32_t id;

    if ((cf->can_id & CAN_EFF_FLAG) != 0U) {
        id = (cf->can_id & CAN_EFF_MASK) | CO_FRAME_EFF;
    } else {
        id = cf->can_id & CAN_SFF_MASK;
    }
    if ((cf->can_id & CAN_RTR_FLAG) != 0U) {
        id |= CO_FRAME_RTR;
    }
    co_frame_set(f, id, cf->data, (cf->len > 8U) ? 8U : cf->len);
}

int co_lx_can_send(int fd, const co_frame_t *f)
{
    struct can_frame cf;
    ssize_t n;

    co_lx_frame_to_can(f, &cf);
    do {
        n = write(fd, &cf, sizeof cf);
    } while ((n < 0) && (errno == EINTR));
    if (n == (ssize_t)sizeof cf) {
        return 0;
    }
    if ((n < 0) && ((errno == ENOBUFS) || (errno == EAGAIN) || (errno == EWOULDBLOCK))) {
        return 1;
    }
    if (n >= 0) {
        errno = EIO;
    }
    return -1;
}

int co_lx_can_recv(int fd, struct can_frame *cf, struct timeval *ts, uint32_t *dropped)
{
    union {
        char buf[CMSG_SPACE(sizeof(struct timeval)) + CMSG_SPACE(sizeof(uint32_t))];
        struct cmsghdr align;
    } ctl;
    struct iovec iov;
    struct msghdr msg;
    struct cmsghdr *c;
    bool have_ts = false;
    ssize_t n;

    iov.iov_base = cf;
    iov.iov_len = sizeof *cf;
    (void)memset(&msg, 0, sizeof msg);
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1U;
    msg.msg_control = ctl.buf;
    msg.msg_controllen = sizeof ctl.buf;
    do {
        n = recvmsg(fd, &msg, 0);
    } while ((n < 0) && (errno == EINTR));
    if (n < 0) {
        return ((errno == EAGAIN) || (errno == EWOULDBLOCK)) ? 0 : -1;
    }
    if (n != (ssize_t)sizeof *cf) {
        errno = EIO;   /* CAN FD frames are not bound for a classic socket */
        return -1;
    }
    for (c = CMSG_FIRSTHDR(&msg); c != NULL; c = CMSG_NXTHDR(&msg, c)) {
        if ((c->cmsg_level == SOL_SOCKET) && (c->cmsg_type == SO_TIMESTAMP) && (ts != NULL)) {
            (void)memcpy(ts, CMSG_DATA(c), sizeof *ts);
            have_ts = true;
        } else if ((c->cmsg_level == SOL_SOCKET) && (c->cmsg_type == SO_RXQ_OVFL) &&
                   (dropped != NULL)) {
            (void)memcpy(dropped, CMSG_DATA(c), sizeof *dropped);
        } else {
            /* not asked for */
        }
    }
    if ((ts != NULL) && !have_ts) {
        (void)gettimeofday(ts, NULL);
    }
    return 1;
}

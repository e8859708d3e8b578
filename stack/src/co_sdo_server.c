/*
 * SDO server: expedited, segmented and block transfer (CiA 301, 7.2.4).
 *
 * Nothing is copied that the dictionary already holds: uploads read from the
 * value by offset (block retransmission reads again), downloads of strings
 * and DOMAINs go to the dictionary as they arrive, which gathers them in the
 * device's staging area and commits them whole (co_od_write_part). Values
 * of fixed size (at most 8 bytes) are gathered here, so they are checked and
 * committed whole too: a rejected or aborted download leaves the old value.
 *
 * One state machine: an open transfer's state names the request it waits
 * for (a segment's command, or with block transfer want[]: byte 0 under a
 * mask), every handler returns an error code,
 * and one abort path (sdo_abort) answers it and ends the transfer.
 */
#include <string.h>

#include "co/co_endian.h"
#include "co/co_sdo.h"
#include "co_priv.h"
#if CO_SDO_BLOCK
#include "co_crc16.h"
#endif

#define SDO_BLKSIZE 127U /* segments per block the server asks for */
#define SEG 7U           /* data bytes per segment */
#define SDO_CHUNK 8U     /* block upload: segments read from the value at once */

/* The states (the fuzzer takes 0 for idle): the request an open transfer
 * waits for (a segment of its direction; a block state's want[state -
 * S_BLK_DL_END]; S_BLK_DL and S_STORE: none). */
enum {
    S_IDLE = 0,
    S_DL_SEG,     /* segmented download */
    S_UL_SEG,     /* segmented upload */
#if CO_SDO_BLOCK
    S_BLK_DL_END, /* block download: waiting for the end request */
    S_BLK_UL_INI, /* block upload: waiting for the start command */
    S_BLK_UL,     /* block upload: sending / waiting for the acknowledge */
    S_BLK_UL_END, /* block upload: waiting for the client's end response */
    S_BLK_DL,     /* block download: receiving a sub-block (any byte 0) */
#endif
    S_STORE       /* a download started a save: its answer waits until it is durable */
};

/* Inlining, per build. Where the build is for speed (CO_FAST): SDO_RARE,
 * the requests that are not an initiate, stay out of sdo_rx (their stack
 * frame would be paid by every expedited transfer), and SDO_CALL, small
 * helpers with many callers, are inlined; at -Os the other way round
 * (fewer bytes). The helpers that open a transfer (open_xfer,
 * open_upload) the compiler places (out of line in a build with block
 * transfer: bench-size BLK 32 bytes more). */
#if CO_FAST
#define SDO_RARE CO_NOINLINE
#define SDO_CALL
#else
#define SDO_RARE
#define SDO_CALL CO_NOINLINE
#endif

/* flags */
#define F_SIZE   0x01U /* size indicated */
#define F_STAGED 0x02U /* buf holds the first chunk of an upload */
#define F_CRC    CO_SDO_BLK_CRC /* both sides use CRC (block; the client's
                                 * bit in a block initiate: taken as it is) */
#define F_LAST   0x08U /* block upload: the last segment has been sent */
#define F_TOGGLE CO_SDO_TOGGLE /* segmented: the toggle bit of the next segment */

/* The eight bytes of an answer: command byte, index, sub-index, four data
 * bytes. */
static void pack_answer(uint8_t *d, uint8_t cmd, uint16_t index, uint8_t sub, uint32_t data)
{
    d[0] = cmd;
    co_put_u16(&d[1], index);
    d[3] = sub;
    co_put_u32(&d[4], data);
}

/* The eight data bytes of @p f go out on the server's COB-ID (a build for
 * speed: at once when nothing waits), or wait as the node's held answer. */
SDO_CALL static void send8(co_node_t *node, co_frame_t *f)
{
    if (CO_FAST) {
        f->id = 0x580UL + node->node_id;
        f->dlc = 8U;
        if (co_tx_now(node, f)) {
            return;
        }
    }
    co_tx_hold(node, CO_TXH_SDO, f->data);
}

/* An answer, packed into the frame (no 8-byte image copied; at -Os one
 * copy: inlined, the answers' callers would grow more than it shrinks). */
SDO_CALL static void reply(co_node_t *node, uint8_t cmd, uint16_t index, uint8_t sub,
                           uint32_t data)
{
    co_frame_t f;

    pack_answer(f.data, cmd, index, sub, data);
    send8(node, &f);
}

SDO_CALL static void sdo_reset(co_node_t *node)
{
    node->sdo.state = (uint8_t)S_IDLE;
    node->sdo.entry = NULL;
}

/* The one abort path: the abort names the open transfer's object, or with
 * nothing open @p index / @p sub (the request's); the transfer ends. */
static void sdo_abort(co_node_t *node, uint16_t index, uint8_t sub, co_err_t err)
{
    const co_sdo_srv_t *t = &node->sdo;
    bool open = t->entry != NULL;

    reply(node, CO_SDO_B0(CO_SDO_CS_ABORT), open ? t->entry->index : index,
          open ? t->desc.sub : sub, (uint32_t)err);
    sdo_reset(node);
}

SDO_CALL static void start(co_node_t *node, uint8_t state)
{
    node->sdo.state = state;
    node->sdo.deadline = node->now + (1000U * (uint32_t)node->sdo.timeout_ms);
}

/* The transfer state of t->desc (the initiate's lookup wrote it there:
 * nothing is open when an initiate comes) of @p e, @p size bytes (F_SIZE in
 * @p flags: indicated), nothing done yet. */
static void open_xfer(co_sdo_srv_t *t, const co_od_entry_t *e, uint32_t size, uint8_t flags)
{
    t->entry = e;
    t->size = size;
    t->flags = flags;
    t->offset = 0U;
#if CO_SDO_BLOCK
    t->crc = 0U;
    t->seqno = 0U;
#endif
}

/* An indicated size against what has arrived: more than indicated, or at
 * the end (@p last) less. */
static co_err_t check_size(const co_sdo_srv_t *t, uint32_t end, bool last)
{
    co_err_t err = CO_OK;

    if ((t->flags & F_SIZE) != 0U) {
        if (end > t->size) {
            err = CO_ERR_TYPE_TOO_LONG;
        } else if (last && (end < t->size)) {
            err = CO_ERR_TYPE_TOO_SHORT;
        } else {
            /* on track */
        }
    }
    return err;
}

/* The next @p len bytes of a download (@p last: the final ones). A value of
 * fixed size is gathered in t->buf (t->offset bytes so far) and written
 * whole at the end; a streamed one goes to the dictionary chunk by chunk. */
static co_err_t write_chunk(co_node_t *node, const uint8_t *data, uint32_t len, bool last)
{
    co_sdo_srv_t *t = &node->sdo;
    uint32_t end = t->offset + len;
    co_err_t err = check_size(t, end, last);

    if (err != CO_OK) {
        return err;
    }
    if (!co_od_is_streamed(&t->desc)) {
        if (end > sizeof t->buf) {
            return CO_ERR_TYPE_MISMATCH;
        }
        co_copy(&t->buf[t->offset], data, len);
        if (last) {
            err = co_od_write_value(node, t->entry, &t->desc, t->buf, end);
        }
    } else {
        co_od_chunk_t c = {NULL, NULL, NULL, NULL, t->offset, (uint8_t *)(uintptr_t)data,
                           len, t->size, last};
        err = co_od_write_part(node, t->entry, &t->desc, &c);
    }
    t->offset = end;
    if (last) {
        co_rx_settle(node); /* a COB-ID written: the receive set (the port's filters) */
    }
    return err;
}

/* The answer (@p cmd, @p index, @p sub, data 0) that ends a download:
 * sent now, or, when the download started a save or restore (0x1010 /
 * 0x1011) that an asynchronous HAL is still writing, once the set is
 * durable (sdo_process). The object: the transfer's, or, for an expedited
 * download (no transfer state), @p index / @p sub. */
static void download_done(co_node_t *node, uint8_t cmd, uint16_t index, uint8_t sub, bool open)
{
    co_sdo_srv_t *t = &node->sdo;

    if ((CO_STORAGE != 0) && co_store_busy(node)) {
        const co_od_entry_t *e = t->entry;
        /* (an expedited download: its descriptor where a transfer's is) */
        if ((e == NULL) && (co_od_lookup(node, index, sub, &e, &t->desc) != CO_OK)) {
            e = NULL;
        }
        if ((e != NULL) && co_store_is_command(e, &t->desc)) {
            t->entry = e; /* (for an abort of the save: sdo_abort) */
            pack_answer(t->buf, cmd, index, sub, 0U);
            t->state = (uint8_t)S_STORE;
            return;
        }
    }
    if (open) {
        sdo_reset(node); /* (an expedited download opened nothing) */
    }
    reply(node, cmd, index, sub, 0U);
}

/* A segmented or block download of @p s of @p e: an indicated @p size must
 * fit (a value of fixed size must have it exactly, a string or DOMAIN in
 * RAM must hold it); then its transfer state. */
static co_err_t open_download(co_node_t *node, const co_od_entry_t *e, const co_od_sub_t *s,
                              bool size_ind, uint32_t size)
{
    uint8_t fixed = co_type_len(s->type);

    if (!size_ind) {
        /* any size */
    } else if (fixed != 0U) {
        if (size != fixed) {
            return CO_ERR_TYPE_MISMATCH;
        }
    } else if (((s->flags & CO_SUB_HOOKIO) == 0U) && (size > s->size)) {
        return CO_ERR_TYPE_TOO_LONG;
    } else {
        /* a string or DOMAIN that fits, or one a hook takes */
    }
    open_xfer(&node->sdo, e, size_ind ? size : 0U, size_ind ? F_SIZE : 0U);
    return CO_OK;
}

/* @p index / @p sub in the dictionary, readable or (@p write) writable:
 * the lookup and access check of every initiate. */
CO_INLINE co_err_t find_for(const co_node_t *node, uint16_t index, uint8_t sub, bool write,
                           const co_od_entry_t **e, co_od_sub_t *s)
{
    return co_od_lookup_for(node, index, sub, write, e, s);
}

/* Checks common to every upload initiate; reads the first chunk into t->buf
 * with @p c (which also runs the read hook once). */
static co_err_t stage_upload(co_node_t *node, uint16_t index, uint8_t sub, co_od_chunk_t *c,
                             const co_od_entry_t **e, co_od_sub_t *s)
{
    co_err_t err = find_for(node, index, sub, false, e, s);

    if (err == CO_OK) {
        (void)memset(node->sdo.buf, 0, sizeof node->sdo.buf); /* (zeros past the value) */
        err = co_od_read_part(node, *e, s, c);
    }
    return err;
}

/* The transfer state of an upload that goes on segmented or by block, its
 * first chunk staged in t->buf. */
static void open_upload(co_sdo_srv_t *t, const co_od_entry_t *e, const co_od_chunk_t *c)
{
    open_xfer(t, e, c->last ? c->len : c->total,
              (uint8_t)(F_STAGED | ((c->total != 0U) || c->last ? F_SIZE : 0U)));
    t->buf[SEG] = (uint8_t)c->len; /* (at most SEG bytes staged) */
}

/* The server offers expedited transfers only (segmented upload refused:
 * then segmented download and block are too, co_settings.h). */
static bool expedited_only(const co_node_t *node)
{
    return (CO_SET(node, sdo.refused) & CO_SDO_XFER_SEG_UPLOAD) != 0U;
}

/* The whole value is staged and fits an expedited answer (an empty one only
 * when the server offers expedited transfers only). */
static bool fits_expedited(const co_node_t *node, bool last, uint32_t size)
{
    return last && (size <= 4U) && ((size > 0U) || expedited_only(node));
}

/* Expedited upload answer with the @p size bytes staged in t->buf (the
 * bytes past them zero: stage_upload). */
static void send_expedited(co_node_t *node, uint16_t index, uint8_t sub, uint32_t size)
{
    uint32_t n = (size == 0U) ? 1U : size;
    uint32_t data = co_get_u32(node->sdo.buf); /* (zeros past the value: stage_upload) */

    reply(node,
          (uint8_t)(CO_SDO_B0(CO_SDO_SCS_UPLOAD_INITIATE) | CO_SDO_EXPEDITED | CO_SDO_SIZE_IND |
                    ((4U - n) << CO_SDO_N_SHIFT)),
          index, sub, data);
}

/* Read up to @p cap bytes of the value at byte @p at into @p buf; the rest
 * of the @p cap bytes are zeros. */
static co_err_t read_seg(co_node_t *node, uint32_t at, uint8_t *buf, uint32_t cap, uint32_t *got,
                         bool *last)
{
    co_sdo_srv_t *t = &node->sdo;
    co_od_chunk_t c = {NULL, NULL, NULL, NULL, at, buf, cap, 0U, false};
    co_err_t err = CO_OK;

    if ((at == 0U) && ((t->flags & F_STAGED) != 0U)) {
        c.len = t->buf[SEG]; /* the first chunk, read when the upload opened */
        co_copy(buf, t->buf, c.len);
    } else {
        err = co_od_read_part(node, t->entry, &t->desc, &c);
    }
    *got = c.len;
    *last = c.last;
    if ((t->flags & F_SIZE) != 0U) {
        if ((at + *got) > t->size) {
            /* never beyond the size announced (a hook reported a smaller total) */
            *got = (at < t->size) ? (t->size - at) : 0U;
        }
        *last = (at + *got) >= t->size;
    }
    (void)memset(&buf[*got], 0, cap - *got);
    return err;
}

/* A block size (segments per block) out of 1..127. */
CO_INLINE bool bad_blksize(uint8_t n)
{
    return (uint8_t)(n - 1U) >= 127U;
}

/* ------------------------------------------------------------ initiate */

/* A download initiate. Expedited: the value is in the request and written
 * straight from it (no transfer state, no staging copy); a value of fixed
 * size must come with its size: as indicated (else 0x06070010), or without
 * an indication the four bytes, or the object's own size when it is
 * smaller (co_od_download). Else a segmented download opens, or with
 * @p block (a block download initiate) a block download. */
static co_err_t initiate_download(co_node_t *node, const uint8_t *d, uint16_t index, uint8_t sub,
                                  bool block)
{
    bool blk = (CO_SDO_BLOCK != 0) && block;
    bool size_ind = (d[0] & (blk ? CO_SDO_BLK_SIZE_IND : CO_SDO_SIZE_IND)) != 0U;
    bool expedited = !blk && ((d[0] & CO_SDO_EXPEDITED) != 0U);
    uint32_t size = co_get_u32(&d[4]);
    const co_od_entry_t *e;
    co_od_sub_t *s = &node->sdo.desc; /* (nothing is open: the lookup's descriptor goes there) */
    co_err_t err;

    if (expedited) {
        size = size_ind ? (4U - ((uint32_t)(d[0] >> 2U) & 3U)) : 0U;
    }
    if (expedited && CO_FAST) {
        err = co_od_download(node, index, sub, &d[4], size);
        co_rx_settle(node); /* a COB-ID written: the receive set (the port's filters) */
        if (err == CO_OK) {
            download_done(node, CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_INITIATE), index, sub, false);
        }
        return err;
    }
    if (blk && ((d[0] & CO_SDO_BLK_END) != 0U)) {
        return CO_ERR_CMD; /* a block download's end without a transfer */
    }
    if (!expedited && expedited_only(node)) {
        return CO_ERR_CMD;
    }
    err = find_for(node, index, sub, true, &e, s);
    if (err == CO_OK) {
        err = open_download(node, e, s, size_ind, size);
    }
    if (expedited) {
        /* (a build for size: a download of one segment, its data in the
         * request; the size not indicated: four bytes, or the object's own
         * size when it is smaller, as co_od_download) */
        if (err == CO_OK) {
            uint8_t fixed = co_type_len(s->type);
            if (size == 0U) {
                size = ((fixed != 0U) && (fixed < 4U)) ? fixed : 4U;
            }
            err = write_chunk(node, &d[4], size, true);
        }
        if (err == CO_OK) {
            download_done(node, CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_INITIATE), index, sub, true);
        }
        return err;
    }
    if ((err == CO_OK) && !blk &&
        ((CO_SET(node, sdo.refused) & CO_SDO_XFER_SEG_DOWNLOAD) != 0U)) {
        err = CO_ERR_NO_ACCESS; /* the object's own errors come first */
    }
    if (err == CO_OK) {
        uint8_t st = (uint8_t)S_DL_SEG;
        uint8_t cmd = CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_INITIATE);
        uint32_t data = 0U;
#if CO_SDO_BLOCK
        if (blk) {
            node->sdo.flags |= (uint8_t)(d[0] & F_CRC);
            st = (uint8_t)S_BLK_DL;
            cmd = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_CRC |
                            CO_SDO_BLK_INITIATE);
            data = SDO_BLKSIZE;
        }
#endif
        start(node, st);
        reply(node, cmd, index, sub, data);
    }
    return err;
}

/* The answer to an upload initiate whose first chunk is staged: expedited
 * (nothing stays open), else the segmented upload opens. */
static co_err_t respond_upload(co_node_t *node, uint16_t index, uint8_t sub, bool last)
{
    co_sdo_srv_t *t = &node->sdo;

    if (fits_expedited(node, last, t->size)) {
        uint32_t size = t->size;
        sdo_reset(node);
        send_expedited(node, index, sub, size);
        return CO_OK;
    }
    if (expedited_only(node)) {
        return CO_ERR_NO_ACCESS;
    }
    start(node, S_UL_SEG);
    reply(node,
          (uint8_t)(CO_SDO_B0(CO_SDO_SCS_UPLOAD_INITIATE) |
                    (((t->flags & F_SIZE) != 0U) ? CO_SDO_SIZE_IND : 0U)),
          index, sub, t->size);
    return CO_OK;
}

/* Called in S_IDLE (no transfer open): the first chunk staged, the
 * transfer state opened, respond_upload answers (an expedited answer
 * closes it again: one path for the initiates of both kinds). */
static co_err_t initiate_upload(co_node_t *node, const uint8_t *d, uint16_t index, uint8_t sub,
                                bool block)
{
    co_sdo_srv_t *t = &node->sdo;
    bool blk = (CO_SDO_BLOCK != 0) && block; /* a block upload initiate */
    const co_od_entry_t *e;
    co_od_chunk_t c = {NULL, NULL, NULL, NULL, 0U, t->buf, SEG, 0U, false};
    co_err_t err;

    if (blk && ((d[0] & CO_SDO_BLK_SUB_MASK) != CO_SDO_BLK_INITIATE)) {
        return CO_ERR_CMD;
    }
    if (blk && bad_blksize(d[4])) {
        return CO_ERR_BLKSIZE;
    }
    err = stage_upload(node, index, sub, &c, &e, &t->desc); /* (nothing is open) */
    if (err != CO_OK) {
        return err;
    }
    open_upload(t, e, &c);
    if (!blk || ((d[5] != 0U) && ((t->flags & F_SIZE) != 0U) && (t->size <= d[5]))) {
        /* (a block upload: the protocol switch to segmented/expedited) */
        return respond_upload(node, index, sub, c.last);
    }
#if CO_SDO_BLOCK
    t->blksize = d[4];
    t->flags |= (uint8_t)(d[0] & F_CRC);
    start(node, S_BLK_UL_INI);
    reply(node,
          (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_UPLOAD) | CO_SDO_BLK_CRC |
                    (((t->flags & F_SIZE) != 0U) ? CO_SDO_BLK_SIZE_IND : 0U)),
          index, sub, t->size);
#endif
    return CO_OK;
}

/* ------------------------------------------------------------ segmented */

/* A segment of a segmented download (@p up false: its data written) or
 * upload (the next bytes read); transfer_request checked the command,
 * this checks the toggle bit. The answer carries the toggle bit; the
 * last segment ends the transfer. */
static co_err_t segment(co_node_t *node, const uint8_t *d, bool up)
{
    co_sdo_srv_t *t = &node->sdo;
    co_frame_t f;
    uint32_t n;
    bool last;
    co_err_t err;
    uint8_t cmd;

    if (((d[0] ^ t->flags) & F_TOGGLE) != 0U) {
        return CO_ERR_TOGGLE;
    }
    if (up) {
        err = read_seg(node, t->offset, &f.data[1], SEG, &n, &last);
        t->offset += n;
        t->flags &= (uint8_t)~F_STAGED;
        cmd = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_UPLOAD_SEGMENT) | ((SEG - n) << CO_SDO_SEG_N_SHIFT) |
                        (last ? CO_SDO_LAST_SEG : 0U));
    } else {
        last = (d[0] & CO_SDO_LAST_SEG) != 0U;
        err = write_chunk(node, &d[1], SEG - (((uint32_t)d[0] >> CO_SDO_SEG_N_SHIFT) & 7U), last);
        (void)memset(&f.data[1], 0, SEG);
        cmd = CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_SEGMENT);
    }
    if (err != CO_OK) {
        return err;
    }
    f.data[0] = (uint8_t)(cmd | (t->flags & F_TOGGLE));
    t->flags ^= F_TOGGLE;
    if ((CO_STORAGE != 0) && last && !up) {
        /* (the answer may wait for a save; without storage it is the
         * frame below, its data zeros) */
        download_done(node, f.data[0], 0U, 0U, true);
        return CO_OK;
    }
    if (last) {
        sdo_reset(node);
    } else {
        start(node, t->state);
    }
    send8(node, &f);
    return CO_OK;
}

#if CO_SDO_BLOCK
/* ------------------------------------------------------------ block download */

/* Where the last segment of a block download is held until the end request
 * brings its length: in t->buf, after the bytes a value of fixed size has
 * gathered there (at most 8: 0 or 7 of them before a last segment), from
 * its start for a streamed value (which gathers nothing). Returns its place;
 * @p room: the bytes kept of the segment's 7 (1 after 7 gathered: a value of
 * fixed size has at most 8 bytes, so a longer last segment is refused by
 * its length anyway). */
CO_NOINLINE static uint8_t *held_at(co_sdo_srv_t *t, uint32_t *room)
{
    uint32_t at = co_od_is_streamed(&t->desc) ? 0U : t->offset;
    uint32_t left = (uint32_t)sizeof t->buf - at; /* (write_chunk keeps at <= 8) */

    *room = (left < SEG) ? left : SEG;
    return &t->buf[at];
}

/* A segment of a sub-block (the server asks for SDO_BLKSIZE, 127, the
 * largest sequence number: only 0 is out of range). The last segment is
 * held until the end request brings its length (held_at). At the end of the
 * sub-block the last good sequence number is acknowledged (a lost or
 * repeated segment is dropped: the client repeats from there) and the next
 * sub-block counts from 0. */
static co_err_t block_download_segment(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t seq = (uint8_t)(d[0] & (uint8_t)~CO_SDO_BLK_LAST);
    bool last = (d[0] & CO_SDO_BLK_LAST) != 0U;

    if (seq == 0U) {
        return CO_ERR_SEQNO;
    }
    start(node, S_BLK_DL);
    if (seq != (uint8_t)(t->seqno + 1U)) {
        /* lost or repeated: dropped */
    } else if (last) {
        uint32_t room;
        uint8_t *held = held_at(t, &room);
        t->seqno = seq;
        co_copy(held, &d[1], room); /* its length comes with the end */
        start(node, S_BLK_DL_END);
    } else {
        co_err_t err;
        t->seqno = seq;
        if ((t->flags & F_CRC) != 0U) {
            t->crc = co_crc16(t->crc, &d[1], SEG);
        }
        err = write_chunk(node, &d[1], SEG, false);
        if (err != CO_OK) {
            return err;
        }
    }
    if (last || (seq == SDO_BLKSIZE)) {
        reply(node, (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_ACK),
              (uint16_t)(t->seqno | ((uint16_t)SDO_BLKSIZE << 8U)), 0U, 0U);
        t->seqno = 0U;
    }
    return CO_OK;
}

/* (want[] checked the command) */
static co_err_t block_download_end(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint32_t len = SEG - (((uint32_t)d[0] >> CO_SDO_BLK_N_SHIFT) & 7U);
    uint32_t room;
    const uint8_t *held = held_at(t, &room);
    co_err_t err = CO_OK;

    /* (more bytes than were kept: too long for its value of fixed size,
     * which write_chunk refuses before it copies anything) */
    if (((t->flags & F_CRC) != 0U) && (len <= room) &&
        (co_crc16(t->crc, held, len) != co_get_u16(&d[1]))) {
        err = CO_ERR_CRC;
    }
    if (err == CO_OK) {
        err = write_chunk(node, held, len, true);
    }
    if (err == CO_OK) {
        download_done(node, (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_END), 0U,
                      0U, true);
    }
    return err;
}

/* ------------------------------------------------------------ block upload */

/* Send segments of the current sub-block until it is complete or the TX
 * path is full (then co_sdo_process resumes). The value is read a chunk of
 * up to SDO_CHUNK segments at a time (a read hook runs once per chunk, not
 * per segment); what the TX path did not take is read again later.
 * Without @p send the segments are read for the CRC only. */
static co_err_t block_upload_send(co_node_t *node, bool send)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t buf[SDO_CHUNK * SEG];
    uint32_t from = 0U; /* offset of buf[0] in the value */
    uint32_t have = 0U; /* bytes in buf */
    bool end = false;   /* buf reaches the end of the value */
    co_frame_t f;

    f.id = 0x580UL + node->node_id;
    f.dlc = 8U;
    while ((t->seqno < t->blksize) && ((t->flags & F_LAST) == 0U)) {
        uint32_t at = t->offset + ((uint32_t)t->seqno * SEG);
        uint32_t got;
        bool last;

        if (!end && ((at + SEG) > (from + have))) {
            /* the segment is not in buf: the next chunk, up to the end of
             * the sub-block */
            uint32_t cap = (uint32_t)(t->blksize - t->seqno) * SEG;
            co_err_t err = read_seg(node, at, buf, (cap < sizeof buf) ? cap : sizeof buf, &have, &end);
            if (err != CO_OK) {
                return err;
            }
            from = at;
        }
        got = from + have - at;
        if (got > SEG) {
            got = SEG;
        }
        last = end && ((at + got) >= (from + have));
        if (!last && (got < SEG)) {
            return CO_ERR_GENERAL; /* a hook produced a short chunk mid-stream */
        }
        f.data[0] = (uint8_t)((uint8_t)(t->seqno + 1U) | (last ? CO_SDO_BLK_LAST : 0U));
        co_copy(&f.data[1], &buf[at - from], SEG); /* zeros after the end */
        if (send && !co_tx_now(node, &f)) {
            break; /* nothing held back: co_sdo_process sends it again */
        }
        if ((t->flags & F_CRC) != 0U) {
            /* the CRC as the segments go out (an acknowledge of all of them
             * takes it over, co_crc16 need not read them again) */
            t->crc_sent = co_crc16(t->crc_sent, &f.data[1], got);
        }
        t->seqno++;
        /* the client's answer is due one timeout after the last segment */
        t->deadline = node->now + (1000U * (uint32_t)t->timeout_ms);
        if (last) {
            /* The end is known now: keep it as the size (t->buf still
             * holds the staged first chunk, which a retransmission from
             * offset 0 needs). */
            t->size = at + got;
            t->flags |= (uint8_t)(F_LAST | F_SIZE);
        }
    }
    return CO_OK;
}

/* The next sub-block, from the last byte acknowledged (@p send: as
 * block_upload_send). */
static co_err_t next_subblock(co_node_t *node, bool send)
{
    co_sdo_srv_t *t = &node->sdo;

    t->seqno = 0U;
    t->crc_sent = t->crc;
    t->flags &= (uint8_t)~F_LAST;
    start(node, S_BLK_UL);
    return block_upload_send(node, send);
}

/* (want[] checked the command) */
static co_err_t block_upload_ack(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t ackseq = d[1];
    uint32_t acked = (uint32_t)ackseq * SEG;
    uint32_t unused = 0U; /* bytes of the last segment without data */
    bool all = ((t->flags & F_LAST) != 0U) && (ackseq == t->seqno);

    if (ackseq > t->seqno) {
        return CO_ERR_SEQNO;
    }
    if (bad_blksize(d[2])) {
        return CO_ERR_BLKSIZE;
    }
    if (all) {
        unused = t->offset + acked - t->size;
        acked -= unused;
    }
    if ((ackseq < t->seqno) && ((t->flags & F_CRC) != 0U)) {
        /* the rest goes again: the CRC of the acknowledged segments, read
         * again as a sub-block of that many that is not transmitted */
        co_err_t err;
        t->blksize = ackseq;
        err = next_subblock(node, false);
        if (err != CO_OK) {
            return err;
        }
    }
    t->crc = t->crc_sent; /* (without CRC both stay 0) */
    /* (F_STAGED stays: a read at offset 0, the staged chunk, comes only
     * while nothing is acknowledged) */
    t->offset += acked;
    if (all) {
        start(node, S_BLK_UL_END);
        reply(node,
              (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_UPLOAD) | CO_SDO_BLK_END |
                        (unused << CO_SDO_BLK_N_SHIFT)),
              t->crc, 0U, 0U);
        return CO_OK;
    }
    t->blksize = d[2];
    return next_subblock(node, true);
}

#endif /* CO_SDO_BLOCK */

/* ------------------------------------------------------------ dispatch */

static void idle_request(co_node_t *node, const uint8_t *d)
{
    uint16_t index = co_get_u16(&d[1]);
    uint8_t sub = d[3];
    uint8_t ccs = CO_SDO_CS(d[0]);
    co_err_t err = CO_ERR_CMD;
#if CO_SDO_BLOCK
    /* ccs 5 and 6 (7: none) are the initiates of 2 and 1 by block */
    bool block = ccs >= CO_SDO_CCS_BLOCK_UPLOAD;

    if (block && (((CO_SET(node, sdo.refused) & CO_SDO_XFER_BLOCK) != 0U) ||
                  expedited_only(node))) {
        /* block refused */
    } else if ((ccs == CO_SDO_CCS_DOWNLOAD_INITIATE) || (ccs == CO_SDO_CCS_BLOCK_DOWNLOAD)) {
        err = initiate_download(node, d, index, sub, block); /* (the most frequent first) */
    } else if ((ccs == CO_SDO_CCS_UPLOAD_INITIATE) || (ccs == CO_SDO_CCS_BLOCK_UPLOAD)) {
        err = initiate_upload(node, d, index, sub, block);
#else
    if (ccs == CO_SDO_CCS_DOWNLOAD_INITIATE) {
        err = initiate_download(node, d, index, sub, false); /* (the most frequent first) */
    } else if (ccs == CO_SDO_CCS_UPLOAD_INITIATE) {
        err = initiate_upload(node, d, index, sub, false);
#endif
    } else if ((ccs == CO_SDO_CCS_DOWNLOAD_SEGMENT) || (ccs == CO_SDO_CCS_UPLOAD_SEGMENT)) {
        index = 0U; /* a segment without a transfer carries no index */
        sub = 0U;
    } else {
        /* ccs 7 */
    }
    if (err != CO_OK) {
        sdo_abort(node, index, sub, err);
    }
}

/* A request while a segmented or block transfer is open (not S_BLK_DL):
 * byte 0 must be the one the state waits for (a segment of the transfer's
 * direction; a block state's want[]: mask, value), a segment's toggle bit
 * the expected one. */
SDO_RARE static co_err_t transfer_request(co_node_t *node, const uint8_t *d)
{
#if CO_SDO_BLOCK
    static const uint8_t want[][2] = {
        {0xE3U, CO_SDO_B0(CO_SDO_CCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_END},
        {0xFFU, CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_START},
        {0xE3U, CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_ACK},
        {0xE3U, CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_END},
    };
#endif
    co_sdo_srv_t *t = &node->sdo;
    uint8_t st = t->state;

    if ((CO_STORAGE != 0) && (st == (uint8_t)S_STORE)) { /* (without storage never) */
        /* a new request while the save's answer is pending: refused, the
         * answer still comes */
        reply(node, CO_SDO_B0(CO_SDO_CS_ABORT), co_get_u16(&d[1]), d[3],
              (uint32_t)CO_ERR_STORE_STATE);
        return CO_OK;
    }
    if (st <= (uint8_t)S_UL_SEG) {
        /* a segment of the transfer's direction */
        bool up = st == (uint8_t)S_UL_SEG;
        if (CO_SDO_CS(d[0]) !=
            (up ? CO_SDO_CCS_UPLOAD_SEGMENT : CO_SDO_CCS_DOWNLOAD_SEGMENT)) {
            return CO_ERR_CMD;
        }
        return segment(node, d, up);
    }
#if CO_SDO_BLOCK
    if ((d[0] & want[st - (uint8_t)S_BLK_DL_END][0]) != want[st - (uint8_t)S_BLK_DL_END][1]) {
        return CO_ERR_CMD;
    }
    if (st == (uint8_t)S_BLK_UL_END) {
        sdo_reset(node); /* the client confirmed the end */
        return CO_OK;
    }
    if (st == (uint8_t)S_BLK_UL) {
        return block_upload_ack(node, d);
    }
    if (st == (uint8_t)S_BLK_UL_INI) {
        return next_subblock(node, true);
    }
    return block_download_end(node, d); /* S_BLK_DL_END */
#else
    return CO_OK;
#endif
}

static void sdo_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    co_sdo_srv_t *t = &node->sdo;
    const uint8_t *d = f->data;
    co_err_t err;

    (void)arg;
    if ((node->nmt == (uint8_t)CO_NMT_STOPPED) || co_frame_is_rtr(f)) {
        return;
    }
    if ((f->dlc >= 1U) && (CO_SDO_CS(d[0]) == CO_SDO_CS_ABORT)
#if CO_SDO_BLOCK
        && ((t->state != (uint8_t)S_BLK_DL) || (d[0] == CO_SDO_B0(CO_SDO_CS_ABORT)))
#endif
    ) {
        /* client abort, whatever its length: CiA 301 makes the abort
         * unconfirmed, so nothing answers it; the transfer ends (in a
         * sub-block, byte 0 is a sequence number: only 0x80 aborts);
         * with nothing open nothing happens */
        sdo_reset(node);
    } else if (f->dlc != 8U) {
        /* CiA 301: SDO frames are 8 bytes; anything else is not a valid
         * request (with nothing open, the abort names what it carries) */
        sdo_abort(node, (f->dlc >= 3U) ? co_get_u16(&d[1]) : 0U, (f->dlc >= 4U) ? d[3] : 0U,
                  CO_ERR_CMD);
    } else if (t->state == (uint8_t)S_IDLE) {
        idle_request(node, d);
    } else {
#if CO_SDO_BLOCK
        if (t->state == (uint8_t)S_BLK_DL) {
            err = block_download_segment(node, d);
        } else
#endif
        {
            err = transfer_request(node, d);
        }
        if (err != CO_OK) {
            sdo_abort(node, 0U, 0U, err);
        }
    }
    if (t->state == (uint8_t)S_IDLE) {
        co_svc_untouch(node, CO_ROW_SDO); /* answered, nothing open: no timer */
    }
}

static uint32_t sdo_process(co_node_t *node, uint32_t next)
{
    co_sdo_srv_t *t = &node->sdo;
    co_err_t err = CO_OK;
    uint32_t due = next;

    if (t->state == (uint8_t)S_IDLE) {
        return next;
    }
    if ((CO_STORAGE != 0) && (t->state == (uint8_t)S_STORE)) { /* (without storage never) */
        if (!co_store_busy(node)) {
            err = co_store_result(node);
            if (err == CO_OK) {
                co_frame_t f;
                (void)memcpy(f.data, t->buf, 8U);
                sdo_reset(node);
                send8(node, &f);
            }
        }
        /* no timeout: the HAL's writing takes what it takes; look again
         * in a millisecond (the storage service polls the HAL as often) */
        due = co_deadline_min(node->now, due, node->now + 1000U);
    } else if (co_time_reached(node->now, t->deadline)) {
        err = CO_ERR_TIMEOUT;
    } else {
#if CO_SDO_BLOCK
        if (t->state == (uint8_t)S_BLK_UL) {
            err = block_upload_send(node, true); /* (nothing when the sub-block is out) */
            if ((t->seqno < t->blksize) && ((t->flags & F_LAST) == 0U)) {
                /* TX path still full: try again in a millisecond */
                due = co_deadline_min(node->now, due, node->now + 1000U);
            }
        }
#endif
        due = co_deadline_min(node->now, due, t->deadline);
    }
    if (err != CO_OK) {
        sdo_abort(node, 0U, 0U, err);
    }
    return due;
}

/* ------------------------------------------------------------ service */

/* The server starts over at a reset (its events, CO_SVC_START) and in
 * Stopped (no SDO there: an open transfer ends silently). */
static void sdo_event(co_node_t *node, uint8_t ev)
{
    if (ev == CO_SVC_SLOTS) {
        co_rx_add(node, (uint16_t)(0x600U + node->node_id), CO_ROW_SDO);
    } else if ((ev < CO_SVC_SLOTS) || (node->nmt == (uint8_t)CO_NMT_STOPPED)) {
        sdo_reset(node);
    } else {
        /* nothing to do */
    }
}

const co_service_t co_svc_sdo = {
    sdo_event, sdo_rx, sdo_process,
};

/*
 * SDO server: expedited, segmented and block transfer (CiA 301, 7.2.4).
 *
 * Nothing is copied that the dictionary already holds: uploads read from the
 * value by offset (block retransmission reads again), downloads of strings
 * and DOMAINs go to the dictionary as they arrive, which gathers them in the
 * device's staging area and commits them whole (co_od_write_part). Values
 * of fixed size (at most 8 bytes) are gathered here, so they are checked and
 * committed whole too: a rejected or aborted download leaves the old value.
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

enum {
    S_IDLE = 0,
    S_DL_SEG,     /* segmented download */
    S_UL_SEG,     /* segmented upload */
    S_BLK_DL,     /* block download: receiving a sub-block */
    S_BLK_DL_END, /* block download: waiting for the end request */
    S_BLK_UL_INI, /* block upload: waiting for the start command */
    S_BLK_UL,     /* block upload: sending / waiting for the acknowledge */
    S_BLK_UL_END, /* block upload: waiting for the client's end response */
    S_STORE       /* a download started a save: its answer waits until it is durable */
};

/* flags */
#define F_SIZE   0x01U /* size indicated */
#define F_CRC    0x02U /* both sides use CRC (block) */
#define F_STAGED 0x04U /* buf holds the first chunk of an upload */
#define F_LAST   0x08U /* block upload: the last segment has been sent */

static uint32_t tx_cob(const co_node_t *node)
{
    return 0x580UL + node->node_id;
}

/* The eight bytes of an answer: command byte, index, sub-index, four data
 * bytes. */
static void pack_answer(uint8_t *d, uint8_t cmd, uint16_t index, uint8_t sub, uint32_t data)
{
    d[0] = cmd;
    co_put_u16(&d[1], index);
    d[3] = sub;
    co_put_u32(&d[4], data);
}

/* An answer, packed into the frame (no 8-byte image copied). */
static void reply(co_node_t *node, uint8_t cmd, uint16_t index, uint8_t sub, uint32_t data)
{
    co_frame_t f;

    f.id = tx_cob(node);
    f.dlc = 8U;
    pack_answer(f.data, cmd, index, sub, data);
    co_tx_frame(node, &f);
}

/* An answer given as its eight bytes. */
static void send8(co_node_t *node, const uint8_t *d)
{
    reply(node, d[0], co_get_u16(&d[1]), d[3], co_get_u32(&d[4]));
}

static void sdo_reset(co_node_t *node)
{
    node->sdo.state = (uint8_t)S_IDLE;
    node->sdo.entry = NULL;
    node->sdo.desc = NULL;
}

static void abort_at(co_node_t *node, uint16_t index, uint8_t sub, co_err_t err)
{
    reply(node, CO_SDO_B0(CO_SDO_CS_ABORT), index, sub, (uint32_t)err);
    sdo_reset(node);
}

static void abort_cur(co_node_t *node, co_err_t err)
{
    co_sdo_srv_t *t = &node->sdo;
    uint16_t index = (t->entry != NULL) ? t->entry->index : 0U;
    uint8_t sub = (t->desc != NULL) ? t->desc->sub : 0U;

    abort_at(node, index, sub, err);
}

static void start(co_node_t *node, uint8_t state)
{
    node->sdo.state = state;
    node->sdo.deadline = node->now + node->sdo.timeout_us;
}

static bool is_fixed(const co_od_sub_t *s)
{
    return !co_od_is_streamed(s);
}

/* Commit a complete value gathered in t->buf (fixed size), or the final
 * chunk of a streamed value. */
static co_err_t finish_download(co_node_t *node, const uint8_t *data, uint32_t len)
{
    co_sdo_srv_t *t = &node->sdo;
    co_err_t err;

    if (is_fixed(t->desc)) {
        if (((uint32_t)t->buf_len + len) > sizeof t->buf) {
            return CO_ERR_TYPE_MISMATCH;
        }
        co_copy(&t->buf[t->buf_len], data, len);
        t->buf_len = (uint8_t)(t->buf_len + len);
        err = co_od_write_value(node, t->entry, t->desc, t->buf, t->buf_len);
    } else {
        err = co_od_write_part(node, t->entry, t->desc, t->offset, data, len, t->size, true);
    }
    co_rx_settle(node); /* a COB-ID written: the receive set (the port's filters) */
    return err;
}

/* A chunk that is not the last one. */
static co_err_t put_chunk(co_node_t *node, const uint8_t *data, uint32_t len)
{
    co_sdo_srv_t *t = &node->sdo;
    co_err_t err = CO_OK;

    if (is_fixed(t->desc)) {
        if (((uint32_t)t->buf_len + len) > sizeof t->buf) {
            return CO_ERR_TYPE_MISMATCH;
        }
        co_copy(&t->buf[t->buf_len], data, len);
        t->buf_len = (uint8_t)(t->buf_len + len);
    } else {
        err = co_od_write_part(node, t->entry, t->desc, t->offset, data, len, t->size, false);
    }
    if (err == CO_OK) {
        t->offset += len;
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
        const co_od_sub_t *s = t->desc;
        if ((e == NULL) && (co_od_lookup(node, index, sub, &e, &s) != CO_OK)) {
            e = NULL;
        }
        if ((e != NULL) && co_store_is_command(e, s)) {
            t->entry = e; /* (for an abort of the save: abort_cur) */
            t->desc = s;
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
    co_sdo_srv_t *t = &node->sdo;
    uint8_t fixed = co_type_len(s->type);

    if (size_ind && (fixed != 0U) && (size != fixed)) {
        return CO_ERR_TYPE_MISMATCH;
    }
    if (size_ind && (fixed == 0U) && ((s->flags & CO_SUB_HOOKIO) == 0U) && (size > s->size)) {
        return CO_ERR_TYPE_TOO_LONG;
    }
    t->entry = e;
    t->desc = s;
    t->size = size_ind ? size : 0U;
    t->flags = size_ind ? F_SIZE : 0U;
    t->offset = 0U;
    t->buf_len = 0U;
    t->toggle = 0U;
    t->crc = 0U;
    t->seqno = 0U;
    return CO_OK;
}

/* @p index / @p sub in the dictionary, readable or (@p write) writable:
 * the lookup and access check of every initiate. */
CO_INLINE co_err_t find_for(const co_node_t *node, uint16_t index, uint8_t sub, bool write,
                           const co_od_entry_t **e, const co_od_sub_t **s)
{
    return co_od_lookup_for(node, index, sub, write, e, s);
}

/* Checks common to every upload initiate; reads the first chunk into t->buf
 * (which also runs the read hook once). */
static co_err_t stage_upload(co_node_t *node, uint16_t index, uint8_t sub, co_od_chunk_t *c,
                             const co_od_entry_t **e, const co_od_sub_t **s)
{
    co_err_t err = find_for(node, index, sub, false, e, s);

    if (err == CO_OK) {
        c->buf = node->sdo.buf;
        c->offset = 0U;
        c->cap = SEG;
        err = co_od_read_part(node, *e, *s, c);
    }
    return err;
}

/* The transfer state of an upload that goes on segmented or by block, its
 * first chunk staged in t->buf. */
static void open_upload(co_sdo_srv_t *t, const co_od_entry_t *e, const co_od_sub_t *s,
                        const co_od_chunk_t *c)
{
    t->entry = e;
    t->desc = s;
    t->size = c->last ? c->len : c->total;
    t->flags = (uint8_t)(F_STAGED | ((c->total != 0U) || c->last ? F_SIZE : 0U));
    t->buf_len = (uint8_t)c->len;
    t->offset = 0U;
    t->toggle = 0U;
    t->crc = 0U;
    t->seqno = 0U;
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
 * bytes past them zero). */
static void send_expedited(co_node_t *node, uint16_t index, uint8_t sub, uint32_t size)
{
    uint32_t n = (size == 0U) ? 1U : size;
    uint32_t data = co_get_u32(node->sdo.buf);

    if (size < 4U) {
        uint32_t keep = ((uint32_t)1U << (8U * size)) - 1U;
        data &= keep;
    }
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
    co_od_chunk_t c = {buf, at, cap, 0U, 0U, false};
    co_err_t err = CO_OK;

    if ((at == 0U) && ((t->flags & F_STAGED) != 0U)) {
        c.len = t->buf_len; /* the first chunk, read when the upload opened */
        co_copy(buf, t->buf, c.len);
    } else {
        err = co_od_read_part(node, t->entry, t->desc, &c);
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

/* ------------------------------------------------------------ initiate */

/* A download initiate. Expedited: the value is in the request and written
 * straight from it (no transfer state, no staging copy); a value of fixed
 * size must come with its size: as indicated (else 0x06070010), or without
 * an indication the four bytes, or the object's own size when it is
 * smaller (co_od_download). Else a segmented download opens. */
static void initiate_download(co_node_t *node, const uint8_t *d, uint16_t index, uint8_t sub)
{
    bool size_ind = (d[0] & CO_SDO_SIZE_IND) != 0U;
    uint32_t size = co_get_u32(&d[4]);
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    co_err_t err;

    if ((d[0] & CO_SDO_EXPEDITED) != 0U) {
        size = size_ind ? (4U - ((uint32_t)(d[0] >> 2U) & 3U)) : 0U;
        err = co_od_download(node, index, sub, &d[4], size);
        co_rx_settle(node); /* a COB-ID written: the receive set (the port's filters) */
        if (err != CO_OK) {
            abort_at(node, index, sub, err);
            return;
        }
        download_done(node, CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_INITIATE), index, sub, false);
        return;
    }
    if (expedited_only(node)) {
        err = CO_ERR_CMD;
    } else {
        err = find_for(node, index, sub, true, &e, &s);
    }
    if (err == CO_OK) {
        err = open_download(node, e, s, size_ind, size);
    }
    if ((err == CO_OK) && ((CO_SET(node, sdo.refused) & CO_SDO_XFER_SEG_DOWNLOAD) != 0U)) {
        err = CO_ERR_NO_ACCESS; /* the object's own errors come first */
    }
    if (err != CO_OK) {
        abort_at(node, index, sub, err);
        return;
    }
    start(node, S_DL_SEG);
    reply(node, CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_INITIATE), index, sub, 0U);
}

static void respond_upload(co_node_t *node, bool last)
{
    co_sdo_srv_t *t = &node->sdo;
    uint16_t index = t->entry->index;
    uint8_t sub = t->desc->sub;

    if (fits_expedited(node, last, t->size)) {
        uint32_t size = t->size;
        sdo_reset(node);
        send_expedited(node, index, sub, size);
        return;
    }
    if (expedited_only(node)) {
        abort_at(node, index, sub, CO_ERR_NO_ACCESS);
        return;
    }
    start(node, S_UL_SEG);
    reply(node,
          (uint8_t)(CO_SDO_B0(CO_SDO_SCS_UPLOAD_INITIATE) |
                    (((t->flags & F_SIZE) != 0U) ? CO_SDO_SIZE_IND : 0U)),
          index, sub, t->size);
}

/* Called in S_IDLE (no transfer open): an expedited answer leaves it so. */
static void initiate_upload(co_node_t *node, uint16_t index, uint8_t sub)
{
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    co_od_chunk_t c;
    co_err_t err = stage_upload(node, index, sub, &c, &e, &s);

    if (err != CO_OK) {
        abort_at(node, index, sub, err);
    } else if (fits_expedited(node, c.last, c.len)) {
        send_expedited(node, index, sub, c.len);
    } else {
        open_upload(&node->sdo, e, s, &c);
        respond_upload(node, c.last);
    }
}

/* ------------------------------------------------------------ segmented */

static void download_segment(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t toggle = (uint8_t)(d[0] & CO_SDO_TOGGLE);
    uint32_t len = SEG - (((uint32_t)d[0] >> CO_SDO_SEG_N_SHIFT) & 7U);
    bool last = (d[0] & CO_SDO_LAST_SEG) != 0U;
    co_err_t err = CO_OK;

    if (toggle != t->toggle) {
        abort_cur(node, CO_ERR_TOGGLE);
        return;
    }
    if ((t->flags & F_SIZE) != 0U) {
        uint32_t end = t->offset + len;
        if (end > t->size) {
            err = CO_ERR_TYPE_TOO_LONG;
        } else if (last && (end < t->size)) {
            err = CO_ERR_TYPE_TOO_SHORT;
        } else {
            /* on track */
        }
    }
    if (err == CO_OK) {
        err = last ? finish_download(node, &d[1], len) : put_chunk(node, &d[1], len);
    }
    if (err != CO_OK) {
        abort_cur(node, err);
        return;
    }
    {
        uint8_t cmd = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_DOWNLOAD_SEGMENT) | toggle);
        t->toggle ^= CO_SDO_TOGGLE;
        if (last) {
            download_done(node, cmd, 0U, 0U, true);
        } else {
            start(node, S_DL_SEG);
            reply(node, cmd, 0U, 0U, 0U);
        }
    }
}

static void upload_segment(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t toggle = (uint8_t)(d[0] & CO_SDO_TOGGLE);
    uint8_t r[8] = {0};
    uint32_t got = 0U;
    bool last = false;
    co_err_t err;

    if (toggle != t->toggle) {
        abort_cur(node, CO_ERR_TOGGLE);
        return;
    }
    err = read_seg(node, t->offset, &r[1], SEG, &got, &last);
    if (err != CO_OK) {
        abort_cur(node, err);
        return;
    }
    t->flags &= (uint8_t)~F_STAGED;
    t->offset += got;
    r[0] = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_UPLOAD_SEGMENT) | toggle | ((SEG - got) << CO_SDO_SEG_N_SHIFT) |
                     (last ? CO_SDO_LAST_SEG : 0U));
    t->toggle ^= CO_SDO_TOGGLE;
    if (last) {
        sdo_reset(node);
    } else {
        start(node, S_UL_SEG);
    }
    send8(node, r);
}

#if CO_SDO_BLOCK
/* ------------------------------------------------------------ block download */

static void block_download_initiate(co_node_t *node, const uint8_t *d, uint16_t index,
                                    uint8_t sub)
{
    bool size_ind = (d[0] & CO_SDO_BLK_SIZE_IND) != 0U;
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    co_err_t err;

    if ((d[0] & CO_SDO_BLK_END) != 0U) {
        abort_at(node, index, sub, CO_ERR_CMD); /* end without a transfer */
        return;
    }
    err = find_for(node, index, sub, true, &e, &s);
    if (err == CO_OK) {
        err = open_download(node, e, s, size_ind, co_get_u32(&d[4]));
    }
    if (err != CO_OK) {
        abort_at(node, index, sub, err);
        return;
    }
    if ((d[0] & CO_SDO_BLK_CRC) != 0U) {
        node->sdo.flags |= F_CRC;
    }
    node->sdo.blksize = (uint8_t)SDO_BLKSIZE;
    start(node, S_BLK_DL);
    reply(node, (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_CRC | CO_SDO_BLK_INITIATE),
          index, sub, SDO_BLKSIZE);
}

static void block_ack(co_node_t *node)
{
    uint8_t r[8] = {0};

    r[0] = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_ACK);
    r[1] = node->sdo.seqno;
    r[2] = node->sdo.blksize;
    send8(node, r);
}

static void block_download_segment(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t seq = (uint8_t)(d[0] & (uint8_t)~CO_SDO_BLK_LAST);
    bool last = (d[0] & CO_SDO_BLK_LAST) != 0U;
    co_err_t err;

    if ((seq == 0U) || (seq > t->blksize)) {
        abort_cur(node, CO_ERR_SEQNO);
        return;
    }
    start(node, S_BLK_DL);
    if (seq != (uint8_t)(t->seqno + 1U)) {
        /* lost or repeated segment: drop it; at the end of the sub-block
         * acknowledge the last good one so the client repeats from there */
        if (last || (seq == t->blksize)) {
            block_ack(node);
            t->seqno = 0U;
        }
        return;
    }
    t->seqno = seq;
    if (last) {
        co_copy(t->held, &d[1], SEG);
        block_ack(node);
        t->seqno = 0U;
        start(node, S_BLK_DL_END);
        return;
    }
    if (((t->flags & F_SIZE) != 0U) && ((t->offset + SEG) > t->size)) {
        abort_cur(node, CO_ERR_TYPE_TOO_LONG);
        return;
    }
    if ((t->flags & F_CRC) != 0U) {
        t->crc = co_crc16(t->crc, &d[1], SEG);
    }
    err = put_chunk(node, &d[1], SEG);
    if (err != CO_OK) {
        abort_cur(node, err);
        return;
    }
    if (seq == t->blksize) {
        block_ack(node);
        t->seqno = 0U;
    }
}

static void block_download_end(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint32_t len = SEG - (((uint32_t)d[0] >> CO_SDO_BLK_N_SHIFT) & 7U);
    co_err_t err = CO_OK;

    if ((d[0] & 0xE3U) != (CO_SDO_B0(CO_SDO_CCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_END)) {
        abort_cur(node, CO_ERR_CMD);
        return;
    }
    if ((t->flags & F_SIZE) != 0U) {
        uint32_t end = t->offset + len;
        if (end > t->size) {
            err = CO_ERR_TYPE_TOO_LONG;
        } else if (end < t->size) {
            err = CO_ERR_TYPE_TOO_SHORT;
        } else {
            /* exact */
        }
    }
    if ((err == CO_OK) && ((t->flags & F_CRC) != 0U) &&
        (co_crc16(t->crc, t->held, len) != co_get_u16(&d[1]))) {
        err = CO_ERR_CRC;
    }
    if (err == CO_OK) {
        err = finish_download(node, t->held, len);
    }
    if (err != CO_OK) {
        abort_cur(node, err);
        return;
    }
    download_done(node, (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_DOWNLOAD) | CO_SDO_BLK_END), 0U, 0U,
                  true);
}

/* ------------------------------------------------------------ block upload */

CO_NOINLINE static void block_upload_initiate(co_node_t *node, const uint8_t *d, uint16_t index,
                                              uint8_t sub)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t blksize = d[4];
    uint8_t pst = d[5];
    const co_od_entry_t *e;
    const co_od_sub_t *s;
    co_od_chunk_t c;
    co_err_t err;

    if ((d[0] & CO_SDO_BLK_SUB_MASK) != CO_SDO_BLK_INITIATE) {
        abort_at(node, index, sub, CO_ERR_CMD);
        return;
    }
    if ((blksize == 0U) || (blksize > 127U)) {
        abort_at(node, index, sub, CO_ERR_BLKSIZE);
        return;
    }
    err = stage_upload(node, index, sub, &c, &e, &s);
    if (err != CO_OK) {
        abort_at(node, index, sub, err);
        return;
    }
    open_upload(t, e, s, &c);
    if ((pst != 0U) && ((t->flags & F_SIZE) != 0U) && (t->size <= pst)) {
        respond_upload(node, c.last); /* protocol switch to segmented/expedited */
        return;
    }
    t->blksize = blksize;
    if ((d[0] & CO_SDO_BLK_CRC) != 0U) {
        t->flags |= F_CRC;
    }
    start(node, S_BLK_UL_INI);
    reply(node,
          (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_UPLOAD) | CO_SDO_BLK_CRC |
                    (((t->flags & F_SIZE) != 0U) ? CO_SDO_BLK_SIZE_IND : 0U)),
          index, sub,
          t->size);
}

/* Send segments of the current sub-block until it is complete or the TX
 * path is full (then co_sdo_process resumes). The value is read a chunk of
 * up to SDO_CHUNK segments at a time (a read hook runs once per chunk, not
 * per segment); what the TX path did not take is read again later. */
static void block_upload_send(co_node_t *node)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t buf[SDO_CHUNK * SEG];
    uint32_t from = 0U; /* offset of buf[0] in the value */
    uint32_t have = 0U; /* bytes in buf */
    bool end = false;   /* buf reaches the end of the value */
    co_frame_t f;

    f.id = tx_cob(node);
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
                abort_cur(node, err);
                return;
            }
            from = at;
        }
        got = from + have - at;
        if (got > SEG) {
            got = SEG;
        }
        last = end && ((at + got) >= (from + have));
        if (!last && (got < SEG)) {
            abort_cur(node, CO_ERR_GENERAL); /* a hook produced a short chunk mid-stream */
            return;
        }
        f.data[0] = (uint8_t)((uint8_t)(t->seqno + 1U) | (last ? CO_SDO_BLK_LAST : 0U));
        co_copy(&f.data[1], &buf[at - from], SEG); /* zeros after the end */
        if (!co_tx_now(node, &f)) {
            return; /* nothing held back: co_sdo_process sends it again */
        }
        if ((t->flags & F_CRC) != 0U) {
            /* the CRC as the segments go out (an acknowledge of all of them
             * takes it over, co_crc16 need not read them again) */
            t->crc_sent = co_crc16(t->crc_sent, &f.data[1], got);
        }
        t->seqno++;
        /* the client's answer is due one timeout after the last segment */
        t->deadline = node->now + node->sdo.timeout_us;
        if (last) {
            /* The end is known now: keep it as the size (t->buf_len still
             * holds the staged first chunk, which a retransmission from
             * offset 0 needs). */
            t->size = at + got;
            t->flags |= (uint8_t)(F_LAST | F_SIZE);
        }
    }
}

static co_err_t crc_range(co_node_t *node, uint32_t from, uint32_t len)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t b[SEG];

    while (len > 0U) {
        uint32_t got = 0U;
        bool last = false;
        co_err_t err = read_seg(node, from, b, SEG, &got, &last);
        if (err != CO_OK) {
            return err;
        }
        if (got > len) {
            got = len;
        }
        if (got == 0U) {
            break;
        }
        t->crc = co_crc16(t->crc, b, got);
        from += got;
        len -= got;
    }
    return CO_OK;
}

static void block_upload_ack(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t ackseq = d[1];
    uint8_t blksize = d[2];
    bool all = (t->flags & F_LAST) != 0U;
    uint32_t acked;
    uint32_t tail = 0U; /* bytes in the last segment */
    co_err_t err = CO_OK;

    if (ackseq > t->seqno) {
        abort_cur(node, CO_ERR_SEQNO);
        return;
    }
    if ((blksize == 0U) || (blksize > 127U)) {
        abort_cur(node, CO_ERR_BLKSIZE);
        return;
    }
    all = all && (ackseq == t->seqno);
    if (all) {
        acked = t->size - t->offset;
        tail = acked - ((uint32_t)(ackseq - 1U) * SEG);
    } else {
        acked = (uint32_t)ackseq * SEG;
    }
    if ((t->flags & F_CRC) == 0U) {
        /* no CRC */
    } else if (ackseq == t->seqno) {
        t->crc = t->crc_sent; /* every segment sent is acknowledged */
    } else {
        err = crc_range(node, t->offset, acked); /* the rest goes again */
    }
    if (err != CO_OK) {
        abort_cur(node, err);
        return;
    }
    t->offset += acked;
    if (t->offset > 0U) {
        t->flags &= (uint8_t)~F_STAGED;
    }
    if (all) {
        uint8_t r[8] = {0};
        r[0] = (uint8_t)(CO_SDO_B0(CO_SDO_SCS_BLOCK_UPLOAD) | CO_SDO_BLK_END |
                         ((SEG - tail) << CO_SDO_BLK_N_SHIFT));
        co_put_u16(&r[1], ((t->flags & F_CRC) != 0U) ? t->crc : 0U);
        start(node, S_BLK_UL_END);
        send8(node, r);
        return;
    }
    t->flags &= (uint8_t)~F_LAST;
    t->blksize = blksize;
    t->seqno = 0U;
    t->crc_sent = t->crc;
    start(node, S_BLK_UL);
    block_upload_send(node);
}

#endif /* CO_SDO_BLOCK */

/* ------------------------------------------------------------ dispatch */

static void idle_request(co_node_t *node, const uint8_t *d)
{
    uint16_t index = co_get_u16(&d[1]);
    uint8_t sub = d[3];
    uint8_t ccs = CO_SDO_CS(d[0]);
#if CO_SDO_BLOCK
    bool blocks = ((CO_SET(node, sdo.refused) & CO_SDO_XFER_BLOCK) == 0U) && !expedited_only(node);
#endif

    if (ccs == CO_SDO_CCS_DOWNLOAD_INITIATE) {
        initiate_download(node, d, index, sub); /* (the most frequent first) */
    } else if (ccs == CO_SDO_CCS_UPLOAD_INITIATE) {
        initiate_upload(node, index, sub);
    } else if (ccs == CO_SDO_CS_ABORT) {
        /* abort with nothing open: nothing to do */
#if CO_SDO_BLOCK
    } else if (blocks && (ccs == CO_SDO_CCS_BLOCK_UPLOAD)) {
        block_upload_initiate(node, d, index, sub);
    } else if (blocks && (ccs == CO_SDO_CCS_BLOCK_DOWNLOAD)) {
        block_download_initiate(node, d, index, sub);
#endif
    } else {
        /* ccs 7, block refused, or a segment without a transfer (it
         * carries no index: answered with 0) */
        bool seg = (ccs == CO_SDO_CCS_DOWNLOAD_SEGMENT) || (ccs == CO_SDO_CCS_UPLOAD_SEGMENT);
        abort_at(node, seg ? 0U : index, seg ? 0U : sub, CO_ERR_CMD);
    }
}

/* A frame whose DLC is not 8. CiA 301: SDO frames are 8 bytes; anything
 * else is not a valid request. */
static void bad_length(co_node_t *node, const co_frame_t *f)
{
    const uint8_t *d = f->data;

    if (node->sdo.state == (uint8_t)S_IDLE) {
        abort_at(node, (f->dlc >= 3U) ? co_get_u16(&d[1]) : 0U, (f->dlc >= 4U) ? d[3] : 0U,
                 CO_ERR_CMD);
    } else {
        abort_cur(node, CO_ERR_CMD);
    }
}

/* A request while a segmented or block transfer is open. */
CO_NOINLINE static void transfer_request(co_node_t *node, const uint8_t *d)
{
    co_sdo_srv_t *t = &node->sdo;
    uint8_t ccs = CO_SDO_CS(d[0]);

    switch (t->state) {
    case S_DL_SEG:
        if (ccs == CO_SDO_CCS_DOWNLOAD_SEGMENT) {
            download_segment(node, d);
        } else {
            abort_cur(node, CO_ERR_CMD);
        }
        break;
    case S_UL_SEG:
        if (ccs == CO_SDO_CCS_UPLOAD_SEGMENT) {
            upload_segment(node, d);
        } else {
            abort_cur(node, CO_ERR_CMD);
        }
        break;
#if CO_SDO_BLOCK
    case S_BLK_DL_END:
        block_download_end(node, d);
        break;
    case S_BLK_UL_INI:
        if (d[0] == (CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_START)) {
            t->seqno = 0U;
            t->crc_sent = t->crc;
            t->flags &= (uint8_t)~F_LAST;
            start(node, S_BLK_UL);
            block_upload_send(node);
        } else {
            abort_cur(node, CO_ERR_CMD);
        }
        break;
    case S_BLK_UL:
        if ((d[0] & 0xE3U) == (CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_ACK)) {
            block_upload_ack(node, d);
        } else {
            abort_cur(node, CO_ERR_CMD);
        }
        break;
    case S_BLK_UL_END:
        if ((d[0] & 0xE3U) == (CO_SDO_B0(CO_SDO_CCS_BLOCK_UPLOAD) | CO_SDO_BLK_END)) {
            sdo_reset(node);
        } else {
            abort_cur(node, CO_ERR_CMD);
        }
        break;
#endif
    case S_STORE:
        /* a new request while the save's answer is pending: refused, the
         * answer still comes */
        reply(node, CO_SDO_B0(CO_SDO_CS_ABORT), co_get_u16(&d[1]), d[3],
              (uint32_t)CO_ERR_STORE_STATE);
        break;
    default:
        sdo_reset(node);
        break;
    }
}

static void sdo_rx(co_node_t *node, uint16_t arg, const co_frame_t *f)
{
    co_sdo_srv_t *t = &node->sdo;
    const uint8_t *d = f->data;

    (void)arg;
    if ((node->nmt == (uint8_t)CO_NMT_STOPPED) || co_frame_is_rtr(f)) {
        return;
    }
    if ((t->state == (uint8_t)S_IDLE) && (f->dlc == 8U)) {
        idle_request(node, d); /* (an abort: nothing is open, nothing to do) */
        if (t->state == (uint8_t)S_IDLE) {
            co_svc_untouch(node, CO_ROW_SDO); /* answered, nothing open: no timer */
        }
        return;
    }
    if ((f->dlc >= 1U) && ((t->state != (uint8_t)S_BLK_DL) ? (CO_SDO_CS(d[0]) == CO_SDO_CS_ABORT)
                                                             : (d[0] == CO_SDO_B0(CO_SDO_CS_ABORT)))) {
        /* client abort, whatever its length: CiA 301 makes the abort
         * unconfirmed, so nothing answers it; the transfer ends */
        sdo_reset(node);
        return;
    }
    if (f->dlc != 8U) {
        bad_length(node, f);
        return;
    }
#if CO_SDO_BLOCK
    if (t->state == (uint8_t)S_BLK_DL) {
        block_download_segment(node, d);
        return;
    }
#endif
    transfer_request(node, d); /* (S_IDLE took the 8-byte frames above) */
}

#if CO_SDO_BLOCK
/* A block upload sub-block that the TX path has not taken completely yet. */
static bool upload_pending(const co_sdo_srv_t *t)
{
    return (t->state == (uint8_t)S_BLK_UL) && (t->seqno < t->blksize) &&
           ((t->flags & F_LAST) == 0U);
}
#endif

static uint32_t sdo_process(co_node_t *node, uint32_t next)
{
    co_sdo_srv_t *t = &node->sdo;

    if (t->state == (uint8_t)S_IDLE) {
        return next;
    }
    if ((CO_STORAGE != 0) && (t->state == (uint8_t)S_STORE)) { /* (without storage never) */
        if (!co_store_busy(node)) {
            if (co_store_result(node) == CO_OK) {
                uint8_t r[8];
                (void)memcpy(r, t->buf, 8U);
                sdo_reset(node);
                send8(node, r);
            } else {
                abort_cur(node, co_store_result(node));
            }
        }
        /* no timeout: the HAL's writing takes what it takes; look again
         * in a millisecond (the storage service polls the HAL as often) */
        return co_deadline_min(node->now, next, node->now + 1000U);
    }
    if (co_time_reached(node->now, t->deadline)) {
        abort_cur(node, CO_ERR_TIMEOUT);
        return next;
    }
#if CO_SDO_BLOCK
    if (upload_pending(t)) {
        block_upload_send(node);
        if (upload_pending(&node->sdo)) {
            /* TX path still full: try again in a millisecond */
            next = co_deadline_min(node->now, next, node->now + 1000U);
        }
    }
#endif
    return co_deadline_min(node->now, next, t->deadline);
}

/* ------------------------------------------------------------ service */

static void sdo_reset_kind(co_node_t *node, uint8_t kind)
{
    if (kind == CO_SVC_START) {
        sdo_reset(node);
    }
}

static void sdo_rx_slots(co_node_t *node, uint8_t svc)
{
    co_rx_add(node, (uint16_t)(0x600U + node->node_id), svc);
}

/* No SDO in Stopped: an open transfer ends silently. */
static void sdo_nmt(co_node_t *node, co_nmt_state_t from)
{
    (void)from;
    if (node->nmt == (uint8_t)CO_NMT_STOPPED) {
        sdo_reset(node);
    }
}

const co_service_t co_svc_sdo = {
    NULL, sdo_reset_kind, sdo_rx_slots, sdo_rx, sdo_process, sdo_nmt,
};

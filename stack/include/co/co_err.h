/*
 * One error type for every object-dictionary access. Its values are the
 * CiA 301 SDO abort codes, so an SDO server answers with the value as it is
 * and the application sees the same code the master will see.
 */
#ifndef CO_ERR_H
#define CO_ERR_H

typedef enum co_err {
    CO_OK                    = 0x00000000, /**< success */
    CO_ERR_TOGGLE            = 0x05030000, /**< toggle bit not alternated */
    CO_ERR_TIMEOUT           = 0x05040000, /**< SDO protocol timed out */
    CO_ERR_CMD               = 0x05040001, /**< command specifier not valid or unknown */
    CO_ERR_BLKSIZE           = 0x05040002, /**< invalid block size (block mode) */
    CO_ERR_SEQNO             = 0x05040003, /**< invalid sequence number (block mode) */
    CO_ERR_CRC               = 0x05040004, /**< CRC error (block mode) */
    CO_ERR_NO_MEMORY         = 0x05040005, /**< out of memory */
    CO_ERR_NO_ACCESS         = 0x06010000, /**< unsupported access to an object */
    CO_ERR_WRITE_ONLY        = 0x06010001, /**< attempt to read a write-only object */
    CO_ERR_READ_ONLY         = 0x06010002, /**< attempt to write a read-only object */
    CO_ERR_NO_OBJECT         = 0x06020000, /**< object does not exist */
    CO_ERR_NO_MAP            = 0x06040041, /**< object cannot be mapped to the PDO */
    CO_ERR_MAP_LEN           = 0x06040042, /**< mapped objects exceed the PDO length */
    CO_ERR_PARAM_INCOMPAT    = 0x06040043, /**< general parameter incompatibility */
    CO_ERR_DEV_INCOMPAT      = 0x06040047, /**< general internal incompatibility */
    CO_ERR_HW                = 0x06060000, /**< access failed due to a hardware error */
    CO_ERR_TYPE_MISMATCH     = 0x06070010, /**< data type / length does not match */
    CO_ERR_TYPE_TOO_LONG     = 0x06070012, /**< data type does not match, length too high */
    CO_ERR_TYPE_TOO_SHORT    = 0x06070013, /**< data type does not match, length too low */
    CO_ERR_NO_SUB            = 0x06090011, /**< sub-index does not exist */
    CO_ERR_VALUE             = 0x06090030, /**< invalid value for parameter (download) */
    CO_ERR_VALUE_HIGH        = 0x06090031, /**< value written too high */
    CO_ERR_VALUE_LOW         = 0x06090032, /**< value written too low */
    CO_ERR_MAX_LT_MIN        = 0x06090036, /**< maximum value is less than minimum */
    CO_ERR_RESOURCE          = 0x060A0023, /**< resource not available: SDO connection */
    CO_ERR_GENERAL           = 0x08000000, /**< general error */
    CO_ERR_STORE             = 0x08000020, /**< data cannot be transferred or stored */
    CO_ERR_STORE_LOCAL       = 0x08000021, /**< ... because of local control */
    CO_ERR_STORE_STATE       = 0x08000022, /**< ... because of the present device state */
    CO_ERR_OD_MISSING        = 0x08000023, /**< OD generation failed or no OD present */
    CO_ERR_NO_DATA           = 0x08000024  /**< no data available */
} co_err_t;

/**
 * What setting up a node or binding to it returns (co_node_init,
 * co_od_bind_hook): a configuration result, not an SDO abort code.
 */
typedef enum co_result {
    CO_RESULT_OK = 0,
    CO_RESULT_BAD_CONFIG,   /**< a NULL pointer or missing table in the configuration */
    CO_RESULT_BAD_NODE_ID,  /**< node-ID outside 1..127 */
    CO_RESULT_DEV_INCOMPAT, /**< the device needs a service or option this build of the
                                 core leaves out (co_config.h) */
    CO_RESULT_NO_OBJECT,    /**< no such object in the dictionary */
    CO_RESULT_NO_HOOK_SLOT, /**< the object has no hook slot (description: hook = true) */
    CO_RESULT_HOOK_BOUND,   /**< a hook is already bound there: two plug-ins on one object */
    CO_RESULT_NO_MEMORY     /**< a fixed-size table of the node is full (co_config.h) */
} co_result_t;

#endif /* CO_ERR_H */

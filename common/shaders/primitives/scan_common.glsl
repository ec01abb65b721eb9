// Sizes of the block scan (scan_block.comp, scan_add.comp). Must match kScanBlock in common/gpu/primitives/scan.h.
#define SCAN_THREADS 256u
#define SCAN_BLOCK 512u
// Shared-memory padding: one extra word every 2^SCAN_LOG_BANKS words against bank conflicts.
#define SCAN_LOG_BANKS 5u
#define SCAN_PAD(i) ((i) + ((i) >> SCAN_LOG_BANKS))

// The scan's operator: + (with identity 0), or max with SCAN_MAX (identity 0 too, since the values are uints).
#ifdef SCAN_MAX
#define SCAN_OP(a, b) max(a, b)
#else
#define SCAN_OP(a, b) ((a) + (b))
#endif

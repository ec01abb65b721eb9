// Sizes of the block scan (scan_block.comp, scan_add.comp). Must match kScanBlock in common/gpu/primitives/scan.h.
#define SCAN_THREADS 256u   // scan_add.comp's work group (two elements a thread); scan_block.comp rakes with 64
#define SCAN_BLOCK 512u

// The scan's operator: + (with identity 0), or max with SCAN_MAX (identity 0 too, since the values are uints).
#ifdef SCAN_MAX
#define SCAN_OP(a, b) max(a, b)
#else
#define SCAN_OP(a, b) ((a) + (b))
#endif

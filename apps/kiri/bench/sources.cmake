# Sources of kiri bench (paths relative to apps/kiri/); one file per stage.
list(APPEND KIRI_BENCH_SOURCES
)

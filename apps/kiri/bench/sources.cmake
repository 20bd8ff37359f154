# Sources of kiri bench (paths relative to apps/kiri/); one file per stage.
list(APPEND KIRI_BENCH_SOURCES
  bench/agreement_bench.cpp
  bench/end_to_end_bench.cpp
  bench/fit_bench.cpp
  bench/fog_judge.cpp
  bench/frame_bench.cpp
  bench/froxel_bench.cpp
  bench/froxel_scene.cpp
  bench/layers_bench.cpp
  bench/light_bench.cpp
  bench/light_renderers.cpp
  bench/light_views.cpp
  bench/near_bench.cpp
  bench/layers_scene.cpp
  bench/outputs_bench.cpp
  bench/particles_bench.cpp
  bench/particles_error_bench.cpp
  bench/particles_scene.cpp
  bench/placement_bench.cpp
  bench/presets_bench.cpp
  bench/surface_bench.cpp
  bench/terrain_bench.cpp
  bench/tessellation_bench.cpp
  bench/valley_view.cpp
  bench/views_bench.cpp
)

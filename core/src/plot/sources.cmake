# Owned by the plot module. Paths relative to core/.
set(IMPACTLAB_PLOT_SOURCES
  src/plot/canvas.cpp
  src/plot/font.cpp
  src/plot/render.cpp
  src/plot/ticks.cpp
)

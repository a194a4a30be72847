# Checks a PNG's size from its IHDR chunk (bytes 16-23: width and height, big-endian).
#   cmake -DPNG=file.png -DWIDTH=W -DHEIGHT=H -P png_size.cmake
file(READ ${PNG} header LIMIT 24 HEX)
if(NOT header MATCHES "^89504e470d0a1a0a")
  message(FATAL_ERROR "${PNG}: not a PNG")
endif()
string(SUBSTRING ${header} 32 8 width_hex)
string(SUBSTRING ${header} 40 8 height_hex)
math(EXPR width "0x${width_hex}")
math(EXPR height "0x${height_hex}")
if(NOT width EQUAL WIDTH OR NOT height EQUAL HEIGHT)
  message(FATAL_ERROR "${PNG}: ${width}x${height}, expected ${WIDTH}x${HEIGHT}")
endif()
message(STATUS "${PNG}: ${width}x${height}")

# The browser page (scripts/web.sh writes build-web/impactlab.html) opened from file:// in headless
# Chromium with SwiftShader's WebGL2: the state read back from the page, and a screenshot that must be a
# real picture (web_test.sh says what it checks). Skipped (exit 77) without the page or chromium.
set(IMPACTLAB_WEB_PAGE ${PROJECT_SOURCE_DIR}/build-web/impactlab.html CACHE FILEPATH
    "The page scripts/web.sh builds, for the web test")
add_test(NAME web
         COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/web/web_test.sh ${IMPACTLAB_WEB_PAGE}
                 $<TARGET_FILE:impactlab_png_check> ${CMAKE_CURRENT_BINARY_DIR}/web_test $<TARGET_FILE:impactlab>)
set_tests_properties(web PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 LABELS "web")

// The run as JUnit XML, the format CI servers show as a test list: one <testsuite> per scene, one
// <testcase classname="<scene>" name="<lane>"> per lane and one named "<lane> vs <lane>" per
// cross-lane pair.
#pragma once

#include <string>

#include "harness/gate/run_results.h"

namespace xshade::harness {

// Fail is a <failure>, Error and Crash an <error> (with type "error" or "crash"), Skipped a
// <skipped/>; the message attribute is the first failing layer's detail, the element's text
// every layer and the lane's message. A scene whose verdict none of its test cases carries (it
// failed before any lane ran) gets a test case named "scene" that does, so that CI sees it.
std::string junit_xml(const RunResults& results);

}  // namespace xshade::harness

#include "hlsl_like/prelude.h"

namespace xshade::hlsl {

const std::vector<MacroDefinition>& prelude_macros() {
  static const std::vector<MacroDefinition> macros = [] {
    std::vector<MacroDefinition> list;
    list.push_back({"fixed", "half"});
    for (const char* n : {"1", "2", "3", "4"}) {
      list.push_back({std::string("fixed") + n, std::string("half") + n});
      for (const char* m : {"1", "2", "3", "4"})
        list.push_back({std::string("fixed") + n + "x" + m, std::string("half") + n + "x" + m});
    }
    list.push_back({"UNITY_PI", "3.14159265359f"});
    list.push_back({"UNITY_TWO_PI", "6.28318530718f"});
    list.push_back({"UNITY_FOUR_PI", "12.56637061436f"});
    list.push_back({"UNITY_INV_PI", "0.31830988618f"});
    list.push_back({"UNITY_INV_TWO_PI", "0.15915494309f"});
    list.push_back({"UNITY_HALF_PI", "1.57079632679f"});
    // Unity's matrix macros (UnityShaderVariables.cginc), over the built-in variables the renderer
    // fills by name; a source that declares those variables can use them without Unity's files,
    // and Unity's files redefine them as they like.
    list.push_back({"UNITY_MATRIX_M", "unity_ObjectToWorld"});
    list.push_back({"UNITY_MATRIX_I_M", "unity_WorldToObject"});
    list.push_back({"UNITY_MATRIX_V", "unity_MatrixV"});
    list.push_back({"UNITY_MATRIX_I_V", "unity_MatrixInvV"});
    list.push_back({"UNITY_MATRIX_P", "glstate_matrix_projection"});
    list.push_back({"UNITY_MATRIX_VP", "unity_MatrixVP"});
    list.push_back({"UNITY_MATRIX_MV", "mul(unity_MatrixV, unity_ObjectToWorld)"});
    list.push_back({"UNITY_MATRIX_MVP", "mul(unity_MatrixVP, unity_ObjectToWorld)"});
    list.push_back({"UNITY_MATRIX_T_MV", "transpose(mul(unity_MatrixV, unity_ObjectToWorld))"});
    list.push_back({"UNITY_MATRIX_IT_MV", "transpose(mul(unity_WorldToObject, unity_MatrixInvV))"});
    list.push_back({"XSHADE", "1"});
    return list;
  }();
  return macros;
}

const Result<std::shared_ptr<const PredefinedMacros>>& prelude_table() {
  static const Result<std::shared_ptr<const PredefinedMacros>> table = PredefinedMacros::read(prelude_macros());
  return table;
}

}  // namespace xshade::hlsl

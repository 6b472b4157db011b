// Basic vocabulary of the ShadowPort RHI: handles, errors, the object base class.
//
// Porting rule of thumb: `ID3D11Foo` -> `sp::Foo`, `D3D11_BAR` -> `sp::BAR`, `DXGI_FORMAT_X` ->
// `sp::FORMAT_X`. COM pointers become `sp::Ref<T>` (shared ownership) or stay raw pointers with
// AddRef/Release; a failed call throws `sp::Error` whose message names the call and the object,
// and the D3D11-shaped overloads (descs by pointer, out-pointers) return an HRESULT instead.
#pragma once
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace sp {

template <class T>
using Ref = std::shared_ptr<T>;

// Every validation failure has a stable id (for tests and scripts) and a message for people.
#define SP_ERROR_IDS(X)                                                                        \
  X(DEVICE_CREATION_FAILED)     /* backend could not start (no driver, no EGL, ...) */         \
  X(DEVICE_API_ERROR)           /* the driver rejected a call ShadowPort thought valid */      \
  X(INVALID_ARGUMENT)           /* null pointer, count mismatch, enum out of range */          \
  X(INVALID_DESC)               /* a field of a *_DESC is not allowed */                       \
  X(SIZE_OUT_OF_RANGE)          /* zero or over-limit width/height/bytes/mips/samples */       \
  X(FORMAT_UNSUPPORTED)         /* the format cannot be used this way on this device */        \
  X(BIND_FLAGS_INVALID)         /* resource lacks (or may not have) a bind flag */             \
  X(USAGE_INVALID)              /* usage / CPU access combination not allowed */               \
  X(INITIAL_DATA_INVALID)       /* missing or ill-sized SUBRESOURCE_DATA */                    \
  X(VIEW_FORMAT_INCOMPATIBLE)   /* view format outside the resource's typeless family */       \
  X(VIEW_DIMENSION_INVALID)     /* view dimension does not fit the resource */                 \
  X(SUBRESOURCE_OUT_OF_RANGE)   /* mip/slice/element range outside the resource */             \
  X(SHADER_COMPILE_FAILED)      /* HLSL front end, legaliser, validator or GLSL failure */     \
  X(SHADER_STAGE_MISMATCH)      /* pixel bytecode given to CreateVertexShader, ... */          \
  X(INPUT_LAYOUT_MISMATCH)      /* element not in the VS input signature, bad format ... */    \
  X(SHADER_INTERFACE_MISMATCH)  /* PS reads a semantic the VS does not write */                \
  X(SLOT_OUT_OF_RANGE)          /* StartSlot + Num beyond the D3D11 slot count */              \
  X(UNBOUND_RESOURCE)           /* strict mode: a register the shader reads is unbound */      \
  X(RESOURCE_TYPE_MISMATCH)     /* bound view's dimension/type differs from the shader's */    \
  X(SAMPLE_COUNT_MISMATCH)      /* RTV/DSV/shader disagree on MSAA sample counts */            \
  X(OUTPUT_MISMATCH)            /* render targets of different size, RTV+UAV slot overlap */   \
  X(DRAW_STATE_INVALID)         /* no VS, no input layout, missing vertex/index buffer, ... */ \
  X(COPY_INVALID)               /* Copy* between incompatible resources */                     \
  X(MAP_INVALID)                /* map type not allowed for the usage, double map, ... */      \
  X(QUERY_INVALID)              /* Begin on a timestamp, GetData size mismatch, ... */         \
  X(NOT_SUPPORTED)              /* valid D3D11 but not supported by this backend/driver */     \
  X(OUT_OF_MEMORY)              /* the driver or the host ran out of memory */

enum class ErrorId : uint32_t {
#define SP_X(name) name,
  SP_ERROR_IDS(SP_X)
#undef SP_X
};

std::string_view ErrorIdName(ErrorId id);

// HRESULT, for the D3D11-shaped overloads (out-pointer Create* calls, D3DCompile-style
// compilation) that return a status instead of throwing, so ported code keeps its
// `if (FAILED(hr))` / V_RETURN structure. Values are Windows' own.
using HRESULT = int32_t;
inline constexpr HRESULT S_OK = 0;
inline constexpr HRESULT S_FALSE = 1;
inline constexpr HRESULT E_NOTIMPL = int32_t(0x80004001u);
inline constexpr HRESULT E_FAIL = int32_t(0x80004005u);
inline constexpr HRESULT E_OUTOFMEMORY = int32_t(0x8007000Eu);
inline constexpr HRESULT E_INVALIDARG = int32_t(0x80070057u);
inline constexpr HRESULT DXGI_ERROR_UNSUPPORTED = int32_t(0x887A0004u);
inline constexpr HRESULT DXGI_ERROR_NOT_FOUND = int32_t(0x887A0002u);
inline constexpr HRESULT DXGI_ERROR_MORE_DATA = int32_t(0x887A0003u);
inline constexpr HRESULT DXGI_ERROR_WAS_STILL_DRAWING = int32_t(0x887A000Au);
inline constexpr bool SUCCEEDED(HRESULT hr) { return hr >= 0; }
inline constexpr bool FAILED(HRESULT hr) { return hr < 0; }

// The HRESULT D3D11 returns for a failure of this kind: E_INVALIDARG for invalid arguments,
// descs and uses, DXGI_ERROR_UNSUPPORTED for NOT_SUPPORTED and FORMAT_UNSUPPORTED, E_OUTOFMEMORY
// for OUT_OF_MEMORY, E_FAIL for the rest (driver failures, shaders the driver rejects).
HRESULT HResultFromErrorId(ErrorId id);

// The result of the context calls D3D11 gives an HRESULT that is not an error (Map with
// MAP_FLAG_DO_NOT_WAIT, GetData): true for S_OK, so `if (!ctx->Map(...))` and
// `while (!ctx->GetData(...))` read as before, and the HRESULT itself for D3D11-shaped code
// (`V(ctx->Map(...))`, `while (ctx->GetData(...) == S_FALSE)`). Copying it into a bool is a
// compile error, because S_OK converted to bool would be false.
class CallStatus {
 public:
  constexpr explicit CallStatus(HRESULT hr) : hr_(hr) {}
  constexpr explicit operator bool() const { return hr_ == S_OK; }
  constexpr operator HRESULT() const { return hr_; }
  template <class B>
    requires std::same_as<B, bool>
  operator B() const = delete;

 private:
  HRESULT hr_;
};

// Thrown by every API call that D3D11 would fail (E_INVALIDARG etc.) or whose misuse the D3D11
// debug layer reports. what() reads:
//   "[SP_VIEW_FORMAT_INCOMPATIBLE] CreateShaderResourceView(Texture2D 'shadow map'): ..."
class Error : public std::runtime_error {
 public:
  Error(ErrorId id, std::string call, std::string object, std::string detail);
  ErrorId id() const { return id_; }
  const std::string& call() const { return call_; }
  const std::string& object() const { return object_; }
  const std::string& detail() const { return detail_; }

 private:
  ErrorId id_;
  std::string call_, object_, detail_;
};

// Messages that D3D11's debug layer would print without failing the call (automatic unbinding of
// a resource bound for output, ...) and driver validation output.
enum class MessageSeverity : uint8_t { Info, Warning, Error };

// Windows' GUID, for SetPrivateData / GetPrivateData.
struct GUID {
  uint32_t Data1 = 0;
  uint16_t Data2 = 0, Data3 = 0;
  uint8_t Data4[8] = {};
  friend bool operator==(const GUID&, const GUID&) = default;
};
using REFGUID = const GUID&;
// {429B8C22-9188-4B0C-8742-ACB0BF85C200}: the object's debug name (what DXUT_SetDebugName sets).
inline constexpr GUID WKPDID_D3DDebugObjectName{0x429b8c22, 0x9188, 0x4b0c, {0x87, 0x42, 0xac, 0xb0, 0xbf, 0x85, 0xc2, 0x00}};

class Device;
// D3D11 dynamic shader linkage (ID3D11ClassInstance, ID3D11ClassLinkage) is not supported: these
// exist so ported signatures compile; the calls that take them accept only null.
class ClassInstance;
class ClassLinkage;

namespace detail {
struct BackendObject;  // a backend's data of an object (private)
struct ObjectAccess;
}  // namespace detail

// Base of every device child (resources, views, states, shaders, queries).
class Object : public std::enable_shared_from_this<Object> {
 public:
  virtual ~Object();
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  // SetPrivateData(WKPDID_D3DDebugObjectName) equivalent; used in error messages and passed on
  // to the driver's debug names.
  void SetDebugName(std::string_view name);
  const std::string& GetDebugName() const { return name_; }

  // COM references, for code that keeps raw pointers (`sp::Texture2D* m_pTex; SAFE_RELEASE(m_pTex)`).
  // They count apart from Ref<T> owners: while any is held the object keeps itself alive, and it
  // is destroyed when the last Ref and the last COM reference are gone. Release returns the COM
  // references left (D3D11 returns its total count) and throws sp::Error when none is held.
  // Like the device, not thread-safe.
  uint32_t AddRef();
  uint32_t Release();

  // D3D11's private data. WKPDID_D3DDebugObjectName sets the debug name (dataSize characters,
  // no terminator needed); other GUIDs store a copy of the bytes. Null data removes the entry.
  // GetPrivateData: null data asks for the size; a buffer too small gives DXGI_ERROR_MORE_DATA,
  // an unknown GUID DXGI_ERROR_NOT_FOUND (and *dataSize = 0).
  HRESULT SetPrivateData(REFGUID guid, uint32_t dataSize, const void* data);
  HRESULT GetPrivateData(REFGUID guid, uint32_t* dataSize, void* data) const;

  // "Texture2D 'shadow map' (1024x1024 R32_TYPELESS)" or "Texture2D #7 (...)" when unnamed.
  std::string Describe() const;
  virtual const char* TypeName() const = 0;
  uint64_t UniqueId() const { return uid_; }
  Device* GetDevice() const { return device_; }

 protected:
  explicit Object(Device* device);
  virtual std::string DescribeShape() const { return {}; }
  virtual void OnDebugNameChanged() {}

 private:
  friend class Device;
  friend struct detail::ObjectAccess;
  Device* device_;
  uint64_t uid_;
  std::string name_;
  std::unique_ptr<detail::BackendObject> backend_;
  uint32_t comRefs_ = 0;
  std::shared_ptr<Object> comSelf_;  // held while comRefs_ > 0
  std::vector<std::pair<GUID, std::vector<uint8_t>>> privateData_;
};

// The out-pointer of the D3D11-shaped calls: a COM-style `T**` (it receives an AddRef'd pointer,
// to be Released, as from D3D11), a `Ref<T>*`, or null (`NULL`, `nullptr`). Arrays (the *Get*
// calls) are indexed.
template <class T>
class OutPtr {
 public:
  OutPtr(T** raw) : raw_(raw) {}
  OutPtr(Ref<T>* ref) : ref_(ref) {}
  OutPtr(std::nullptr_t) {}
  // NULL as ported code writes it (an integer constant 0 in C++).
  template <class Int>
    requires std::is_integral_v<Int>
  OutPtr(Int) {}

  bool IsNull() const { return !raw_ && !ref_; }
  void Set(size_t i, Ref<T> value) const {
    if (raw_) {
      if (value) value->AddRef();
      raw_[i] = value.get();
    } else if (ref_) {
      ref_[i] = std::move(value);
    }
  }
  void Set(Ref<T> value) const { Set(0, std::move(value)); }

 private:
  T** raw_ = nullptr;
  Ref<T>* ref_ = nullptr;
};

}  // namespace sp

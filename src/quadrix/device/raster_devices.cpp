// Raster file devices: PNG and PGM/PPM. Both collect the spans of a picture into an Image and
// write it atomically at Close (io/writers.h), so a failed render never leaves a partial file.
#include "quadrix/device/device_internal.h"
#include "quadrix/io/writers.h"

namespace quadrix::device::internal {

namespace {

class PngDevice : public BufferedDevice {
  public:
    explicit PngDevice(DeviceInfo info) { info_ = std::move(info); }

  protected:
    std::string Write(const Image& image) override { return WritePng(info_.path, image); }
};

class PnmDevice : public BufferedDevice {
  public:
    PnmDevice(DeviceInfo info, bool forceRgb) : forceRgb_(forceRgb) { info_ = std::move(info); }

    std::string Open(bool color) override { return BufferedDevice::Open(color || forceRgb_); }

  protected:
    std::string Write(const Image& image) override { return WritePnm(info_.path, image); }

  private:
    bool forceRgb_;
};

}  // namespace

std::unique_ptr<Device> MakePngDevice(DeviceInfo info) {
    return std::make_unique<PngDevice>(std::move(info));
}

std::unique_ptr<Device> MakePnmDevice(DeviceInfo info, bool forceRgb) {
    return std::make_unique<PnmDevice>(std::move(info), forceRgb);
}

}  // namespace quadrix::device::internal

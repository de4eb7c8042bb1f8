// Pieces shared by the device implementations (not part of the device interface).
#pragma once

#include <memory>
#include <string>

#include "quadrix/device/device.h"

namespace quadrix::device::internal {

// A device that collects spans into an image and writes it at Close.
class BufferedDevice : public Device {
  public:
    std::string Open(bool color) override;
    void Span(int row, int x0, int x1, Rgb color) override;
    std::string Close() override;
    void Abort() override { open_ = false; }

  protected:
    // Writes the finished picture; error message or empty.
    virtual std::string Write(const Image& image) = 0;

    Image image_;
    bool open_ = false;
};

// Luminance of a linear RGB color (Rec. 709 weights), 0..255.
std::uint8_t Luminance(Rgb c);

std::unique_ptr<Device> MakeAsciiDevice(DeviceInfo info);
std::unique_ptr<Device> MakePngDevice(DeviceInfo info);
std::unique_ptr<Device> MakePnmDevice(DeviceInfo info, bool forceRgb);
std::unique_ptr<Device> MakeHalftoneDevice(DeviceInfo info, Pattern pattern);
std::unique_ptr<Device> MakeTerminalDevice(DeviceInfo info, std::FILE* screen);

// Lower-case extension of a path including the dot (".png"), empty when none.
std::string Extension(const std::string& path);

}  // namespace quadrix::device::internal

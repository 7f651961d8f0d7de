# The arm-softmmu device configuration of the TSE emulator (replaces QEMU's
# configs/devices/arm-softmmu/default.mak; configured with --without-default-devices).
#
# tse-f407: our STM32F407 machine (emu/hw).  netduinoplus2: QEMU's own STM32F405 machine, kept
# so the same binary can show what the image does on a machine with no clock or CAN controller.
CONFIG_TSE_F407=y
CONFIG_NETDUINOPLUS2=y
# QEMU's STM32F405 SoC maps these but its Kconfig entry does not select them.
CONFIG_STM32F2XX_USART=y
CONFIG_STM32F2XX_TIMER=y
CONFIG_STM32F2XX_ADC=y
CONFIG_STM32F2XX_SPI=y
CONFIG_UNIMP=y
# -semihosting for test images (never the production image).
CONFIG_SEMIHOSTING=y
CONFIG_ARM_COMPATIBLE_SEMIHOSTING=y

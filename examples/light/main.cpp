// A bean in Davis, California, on a clear June day: the PAR its leaves absorb each hour and
// the carbon they fix (docs/physiology.md). Built and run by the tests.

#include <cmath>
#include <cstdio>

#include "plantarch/Context.h"
#include "plantarch/Light.h"
#include "plantarch/Photosynthesis.h"
#include "plantarch/PlantArchitecture.h"

int main() {
    plantarch::Context ctx;
    plantarch::PlantArchitecture arch(&ctx);
    arch.loadPlantModelFromLibrary("bean");
    arch.buildPlantInstanceFromLibrary(plantarch::vec3(0.0f), 30.0f);

    plantarch::LightModel model(ctx);  // every visible triangle of the Context
    const plantarch::Location davis{38.54, -121.74};
    const plantarch::FarquharParameters leaf;
    double fixed = 0.0;  // mol CO2, net, over the day
    for (const plantarch::WeatherHour& hour : plantarch::clearSkyDay(davis, 2026, 6, 21)) {
        const plantarch::LightResult light = model.compute(plantarch::skyLight(davis, hour));
        double absorbed = 0.0, net = 0.0;  // µmol s-1 over the leaves
        for (std::size_t i = 0; i < model.triangleCount(); ++i) {
            if (ctx.objectDataString(model.objects()[i], "organ") != std::string("leaf")) continue;
            const double area = model.areas()[i];
            absorbed += light.absorbed[i] * area;
            net += plantarch::farquharSunlitShaded(leaf, light.absorbed[i], light.absorbedDirect[i],
                                                   light.sunlit[i], hour.airTemperature)
                       .net *
                   area;
        }
        fixed += net * 3600e-6;
        std::printf("%s  PAR %7.1f  leaves absorb %8.1f and fix %7.2f µmol/s\n",
                    plantarch::formatUTCTime(hour.time).c_str(), hour.par, absorbed, net);
        if (hour.time.hour > 20.0 && hour.time.hour < 21.0)  // the hour of noon in Davis
            plantarch::writeLightData(ctx, model, light);    // absorbed_par per object
    }
    std::printf("over the day the plant fixed %.3f mol CO2 (%.2f g of carbon)\n", fixed,
                fixed * 12.011);
    return fixed > 0.0 && std::isfinite(fixed) ? 0 : 1;
}

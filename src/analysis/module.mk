# Layer: analysis. Modules and the objects of the modules each one uses.
MODULES += analysis assembly
$(OBJDIR)/analysis.o: $(OBJDIR)/assembly.o $(OBJDIR)/contact.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/listing.o $(OBJDIR)/messages.o $(OBJDIR)/model.o $(OBJDIR)/results_gmsh.o $(OBJDIR)/strings.o
$(OBJDIR)/assembly.o: $(OBJDIR)/contact.o $(OBJDIR)/element_catalogue.o $(OBJDIR)/element_library.o $(OBJDIR)/element_types.o $(OBJDIR)/kinds.o $(OBJDIR)/linear_solver.o $(OBJDIR)/model.o $(OBJDIR)/ordering.o
